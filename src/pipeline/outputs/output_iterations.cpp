#include "pipeline/outputs/output_iterations.hpp"

#include "io/atomic_file.hpp"
#include "pipeline/sequence/iteration_log.hpp"
#include "pipeline/sequence/shard.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

IterationsCsvOutput::IterationsCsvOutput(const OutputContext& context)
    : dir_(context.config.output.dir),
      options_(context.config.output.iterations),
      shard_(context.config.shard),
      source_(context.source),
      header_(CsvWriter(iteration_columns()).str()) {}

bool IterationsCsvOutput::enabled(const SequenceJobOptions& config) {
  return config.output.iterations.enabled;
}

const char* IterationsCsvOutput::help() {
  return "  iterations.csv              the optimizer's figures, iteration by iteration "
         "(\"iterations\")\n";
}

// A shard writes iterations.shard-I-of-N.csv; the iterations.csv that `seqmassage merge` builds
// from the shards is named too, as the plan names the merged summary and report.
std::vector<fs::path> IterationsCsvOutput::files(const std::vector<int>&) const {
  std::vector<fs::path> out = {dir_ / iterations_file_name(shard_)};
  if (shard_.sharded()) out.push_back(dir_ / iterations_file_name({}));
  return out;
}

std::vector<fs::path> IterationsCsvOutput::folders() const {
  return {};  // output.dir itself, which the job cleans
}

std::string IterationsCsvOutput::describe(const std::vector<int>& frames) const {
  return "  iterations.csv (the optimized frames among " +
         frames_text(count_in(options_.frames, frames)) + "; shear after every iteration for " +
         frames_text(count_in(options_.shear_frames, frames)) + ")\n";
}

std::vector<std::string> IterationsCsvOutput::check(const std::vector<int>& selected) const {
  std::vector<std::string> warnings = unlisted_frames(options_.frames, selected, "output.iterations.frames");
  for (std::string& w :
       unlisted_frames(options_.shear_frames, selected, "output.iterations.shear_frames"))
    warnings.push_back(std::move(w));
  return warnings;
}

json IterationsCsvOutput::report() const {
  return {{"iterations", iterations_file_name(shard_)}};
}

ResultNames IterationsCsvOutput::results() const {
  return {{}, {iterations_file_name(shard_)}};
}

bool IterationsCsvOutput::wants_shear_per_iteration(int index) const {
  return options_.shear_frames.contains(index);
}

OutputFrame IterationsCsvOutput::encode(const FrameOutcome& f) const {
  OutputFrame out;
  if (!f.result || !(options_.frames.contains(f.index) || options_.shear_frames.contains(f.index)))
    return out;
  const std::vector<std::optional<DistortionSummary>> none;
  const bool with_shear =
      options_.shear_frames.contains(f.index) && f.result->ok && f.shear_per_iteration;
  const std::vector<IterationRow> rows =
      iteration_rows(*f.result, summarize_distortion(*f.shear_before),
                     summarize_distortion(*f.shear_after), with_shear ? *f.shear_per_iteration : none);
  CsvWriter csv(iteration_columns());
  append_iteration_rows(csv, f.index, source_->name(f.index), rows);
  out.record_rows = csv.str().substr(header_.size());
  return out;
}

OutputFinish IterationsCsvOutput::finish(const FinishedFrames& done) const {
  const std::string name = iterations_file_name(shard_);
  const auto rows = done.record_rows.find(kRecordKey);
  write_file_atomic(dir_ / name, header_ + (rows == done.record_rows.end() ? "" : rows->second));
  return {{}, {name}};
}

}  // namespace sm
