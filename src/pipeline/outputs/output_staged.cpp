#include "pipeline/outputs/output_staged.hpp"

#include <cstring>
#include <stdexcept>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "pipeline/sequence/frame_sources.hpp"

namespace sm {
namespace fs = std::filesystem;

fs::path positions_file(const std::string& frame_name) {
  return fs::path("positions") / fs::path(frame_name).replace_extension(".bin");
}

Positions read_positions_file(const fs::path& output_dir, const std::string& frame_name,
                              Eigen::Index n) {
  const fs::path file = output_dir / positions_file(frame_name);
  const std::string bytes = read_file(file);
  if (bytes.size() != size_t(n) * 3 * sizeof(double))
    throw IoError("'" + file.string() + "': " + std::to_string(bytes.size()) +
                  " bytes, but the corrected positions of " + std::to_string(n) +
                  " vertices take " + std::to_string(size_t(n) * 3 * sizeof(double)));
  Positions V(n, 3);
  std::memcpy(V.data(), bytes.data(), bytes.size());
  return V;
}

StagedPositionsOutput::StagedPositionsOutput(const OutputContext& context)
    : config_(context.config), source_(context.source) {}

const FrameSource& StagedPositionsOutput::source() const {
  std::call_once(source_once_, [&] {
    if (!source_) source_ = make_frame_source(config_);  // merge: the input, read again
  });
  return *source_;
}

std::vector<fs::path> StagedPositionsOutput::files(const std::vector<int>& frames) const {
  std::vector<fs::path> out;
  for (int i : frames) out.push_back(config_.output.dir / positions_file(source().name(i)));
  for (const std::string& file : assembled_files()) out.push_back(config_.output.dir / file);
  return out;
}

std::vector<fs::path> StagedPositionsOutput::folders() const {
  return {config_.output.dir / "positions"};
}

std::string StagedPositionsOutput::describe(const std::vector<int>& frames) const {
  std::string text = "  positions/<name>.bin (" + std::to_string(frames.size()) +
                     " files: the corrected positions of each frame)\n";
  if (!config_.shard.sharded()) return text + describe_assembled(frames);
  std::string names;
  for (const std::string& file : assembled_files()) names += (names.empty() ? "" : ", ") + file;
  return text + "  " + names + ": assembled from every shard's positions by seqmassage merge\n";
}

ResultNames StagedPositionsOutput::results() const {
  ResultNames names{{"positions/"}, {}};
  if (config_.shard.sharded()) return names;  // `seqmassage merge` assembles the rest
  for (const std::string& file : assembled_files()) names.before_records.push_back(file);
  return names;
}

OutputFrame StagedPositionsOutput::encode(const FrameOutcome& f) const {
  const Positions& V = *f.output;
  OutputFrame out;
  out.files.emplace_back(
      positions_file(source().name(f.index)),
      std::string(reinterpret_cast<const char*>(V.data()), size_t(V.size()) * sizeof(double)));
  return out;
}

OutputFinish StagedPositionsOutput::finish(const FinishedFrames& done) const {
  if (config_.shard.sharded()) return {};  // `seqmassage merge` assembles them
  const std::vector<std::string> files = assembled_files();
  if (done.frames.empty()) {
    std::string names;
    for (size_t k = 0; k < files.size(); ++k)
      names += (k == 0 ? "" : k + 1 == files.size() ? " and " : ", ") + files[k];
    return {{"no frame was processed, so " + names + (files.size() == 1 ? " was" : " were") +
             " not written"},
            {}};
  }
  int next = 0;
  assemble(done, [&](int k, Eigen::Index n) {
    if (k != next++) throw std::logic_error("positions read out of order");
    return read_positions_file(config_.output.dir, done.names[size_t(k)], n);
  });
  return {{}, {files.begin(), files.end()}};
}

}  // namespace sm
