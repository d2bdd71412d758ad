#include "io/gltf/gltf_resource.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdint>

#include "io/input_file.hpp"
#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;

void throw_gltf_error(const fs::path& file, const std::string& element,
                      const std::string& problem) {
  throw InputError("'" + file.string() + "': " + element + ": " + problem);
}


namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// Whether `uri` starts with a scheme ("http:", "file:"): ALPHA *( ALPHA / DIGIT / + - . ) ":".
bool has_scheme(const std::string& uri) {
  if (uri.empty() || !std::isalpha(uint8_t(uri[0]))) return false;
  for (char c : uri) {
    if (c == ':') return true;
    if (!std::isalnum(uint8_t(c)) && c != '+' && c != '-' && c != '.') return false;
  }
  return false;
}

/// tinygltf 2.7's own decoding (dlib::urldecode: '+' is a space, a bad hex digit counts as 0),
/// which builds the path its callbacks are asked for.
std::string tinygltf_decode(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out += ' ';
    } else if (s[i] == '%' && s.size() > i + 2) {
      out += char((std::max(hex_value(s[i + 1]), 0) << 4) | std::max(hex_value(s[i + 2]), 0));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

/// tinygltf's JoinPath.
std::string tinygltf_join(const std::string& a, const std::string& b) {
  if (a.empty()) return b;
  return a.back() == '/' ? a + b : a + "/" + b;
}

}  // namespace

bool percent_decode(const std::string& uri, std::string& out) {
  out.clear();
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] != '%') {
      out += uri[i];
      continue;
    }
    if (i + 2 >= uri.size() || hex_value(uri[i + 1]) < 0 || hex_value(uri[i + 2]) < 0) return false;
    out += char(hex_value(uri[i + 1]) << 4 | hex_value(uri[i + 2]));
    i += 2;
  }
  return true;
}

fs::path resolve_gltf_resource(const fs::path& model, const std::string& element,
                               const std::string& uri, const char* what) {
  const auto refuse = [&](const std::string& why) {
    throw_gltf_error(model, element + ".uri '" + uri + "'", why);
  };
  std::string name;
  if (!percent_decode(uri, name)) refuse("malformed percent-encoding (a '%' needs two hex digits)");
  if (name.empty()) refuse("empty");
  if (name.find('\0') != std::string::npos) refuse("contains a NUL character");
  if (has_scheme(uri)) {
    refuse("has a URI scheme; only data: URIs and files inside the model's folder are read");
  }
  const fs::path relative(name);
  if (relative.is_absolute() || relative.has_root_name()) {
    refuse("is an absolute path; only files inside the model's folder are read");
  }
  // Lexically first: "a/../../x" escapes even when "a" does not exist.
  int depth = 0;
  for (const fs::path& part : relative) {
    if (part == "..") --depth;
    else if (part != "." && !part.empty()) ++depth;
    if (depth < 0) refuse("resolves outside the model's folder");
  }
  const fs::path dir = model.has_parent_path() ? model.parent_path() : fs::path(".");
  const fs::path file = dir / relative;
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) {
    refuse(std::string(what) + " file '" + file.string() + "' not found");
  }
  // Then through symlinks: the file itself and every folder on the way must stay inside.
  std::error_code ec;
  const fs::path real_dir = fs::canonical(dir, ec);
  const fs::path real_file = ec ? fs::path() : fs::canonical(file, ec);
  if (ec) refuse(std::string(what) + " file '" + file.string() + "': " + ec.message());
  const auto mismatch = std::mismatch(real_dir.begin(), real_dir.end(), real_file.begin(),
                                      real_file.end());
  if (mismatch.first != real_dir.end()) {
    refuse("resolves outside the model's folder (through a symlink, to '" + real_file.string() +
           "')");
  }
  if (!S_ISREG(st.st_mode)) {
    refuse("names " + describe_file_kind(unsigned(st.st_mode)) + ", not a regular file");
  }
  return file;
}

void GltfResourceFiles::add(const std::string& uri, const fs::path& file) {
  files_[tinygltf_join(base_dir_, tinygltf_decode(uri))] = file;
}

tinygltf::FsCallbacks GltfResourceFiles::callbacks() {
  return {&GltfResourceFiles::exists, &GltfResourceFiles::expand, &GltfResourceFiles::read,
          &GltfResourceFiles::write, this};
}

bool GltfResourceFiles::exists(const std::string& path, void* self) {
  return static_cast<GltfResourceFiles*>(self)->files_.count(path) > 0;
}

std::string GltfResourceFiles::expand(const std::string& path, void*) {
  return path;
}

bool GltfResourceFiles::read(std::vector<unsigned char>* out, std::string* err,
                             const std::string& path, void* self) {
  const auto& files = static_cast<GltfResourceFiles*>(self)->files_;
  const auto it = files.find(path);
  if (it == files.end()) {
    if (err) *err += "not a checked resource of this model";
    return false;
  }
  try {  // checked by resolve_gltf_resource, but it may have been replaced since
    const std::string bytes = read_input_file(it->second);
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const Error& e) {
    if (err) *err += e.what();
    return false;
  }
}

bool GltfResourceFiles::write(std::string* err, const std::string&,
                              const std::vector<unsigned char>&, void*) {
  if (err) *err += "this reader writes no files";
  return false;
}

}  // namespace sm
