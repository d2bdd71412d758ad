#include "pipeline/sequence/frame_source.hpp"

#include <algorithm>
#include <cstdio>

#include "io/sha256.hpp"

namespace sm {

std::string short_number(double t) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", t);
  return buffer;
}

std::string frame_label(int i, const std::string& name, std::optional<double> time) {
  std::string text = "frame " + std::to_string(i) + " (" + name;
  if (time) text += ", t = " + short_number(*time) + " s";
  return text + ")";
}

std::string FrameSource::label(int i) const {
  return frame_label(i, name(i), time(i));
}

std::string FrameSource::input_hash(int i, const std::string& fetched) const {
  if (!fetched.empty()) return sha256_hex(fetched);
  const TriMesh mesh = decode(i, fetched).mesh;  // no file of its own: its content
  Sha256 hash;
  hash.update(mesh.V.data(), size_t(mesh.V.size()) * sizeof(double));
  hash.update(mesh.F.data(), size_t(mesh.F.size()) * sizeof(int));
  return hash.hex();
}

TriMesh FrameSource::template_frame(int i) const {
  return decode(i, fetch(i)).mesh;
}

std::string FrameSource::fetch(int) const {
  return {};
}

std::string numbered_frame_name(int i, int count) {
  std::string digits = std::to_string(i);
  const size_t width = std::max<size_t>(4, std::to_string(std::max(count - 1, 0)).size());
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  return "frame_" + digits + ".obj";
}

}  // namespace sm
