#include "pipeline/track/track_merge.hpp"

#include <algorithm>
#include <set>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/options_json.hpp"
#include "pipeline/cluster/frame_record.hpp"
#include "pipeline/cluster/merge.hpp"
#include "pipeline/cluster/output_lock.hpp"
#include "pipeline/outputs/frame_output.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::string rerun(const ShardOptions& shard) {
  return "seqmassage --shard " + format_shard(shard) + " CONFIG";
}

// The shards' config, as each must agree on it.
json shared_config(const json& config) {
  json c = job_config(config);
  c.erase("shard");
  return c;
}

// Throws InputError when a shard ran another build or config than the first.
void verify_same_job(const fs::path& dir, const std::vector<ShardReport>& reports) {
  const ShardReport& first = reports.front();
  std::vector<std::string> problems;
  for (const ShardReport& r : reports) {
    if (r.report.value("job", "") != "track") {
      problems.push_back(r.file + " is not a track job's report");
      continue;
    }
    std::string diff;
    if (r.report.at("versions") != first.report.at("versions"))
      diff = "another seqmassage build: " +
             first_difference(first.report.at("versions"), r.report.at("versions"));
    else if (shared_config(r.report.at("config")) != shared_config(first.report.at("config")))
      diff = "another config: " + first_difference(shared_config(first.report.at("config")),
                                                   shared_config(r.report.at("config")));
    if (!diff.empty()) problems.push_back(r.file + " ran " + diff + " than " + first.file);
  }
  if (problems.empty()) return;
  std::string text = "'" + dir.string() + "': the shards are not of one job:";
  for (const std::string& p : problems) text += "\n  " + p;
  throw InputError(text + "\nrun the odd shards again with the config of the others");
}

// The rows of every shard whose block is complete; what is missing into `problems`.
void collect_rows(const std::vector<ShardReport>& reports, const TrackPlan& plan, int count,
                  std::map<int, json>& rows, std::vector<std::string>& problems) {
  std::map<int, const ShardReport*> by_index;
  for (const ShardReport& r : reports) by_index[r.shard.index] = &r;
  std::map<int, std::string> names;
  for (int i : plan.selected) names[i] = plan.outputs.source->name(i);
  for (int i = 0; i < count; ++i) {
    const ShardOptions shard{i, count};
    const std::vector<int> block = shard_frames(plan.selected, shard);
    const auto it = by_index.find(i);
    if (it == by_index.end()) {
      problems.push_back(shard_label(shard) + ": no " + report_file_name(shard) +
                         (block.empty() ? " (it has no frames)"
                                        : "; missing " + describe_frames(block, names)) +
                         "; run it: " + rerun(shard));
      continue;
    }
    const ShardReport& r = *it->second;
    std::vector<int> listed;
    for (const auto& [index, name] : r.frames) listed.push_back(index);
    if (listed != block) {
      problems.push_back(r.file + ": its frames (" + describe_frames(listed, names) +
                         ") are not " + shard_label(shard) + " of the selection (" +
                         describe_frames(block, names) + "); run it again: " + rerun(shard));
      continue;
    }
    const json& section = r.report.at("shard");
    if (!section.value("complete", false)) {
      problems.push_back(r.file + ": " + shard_label(shard) +
                         " was interrupted before its last frame; run it again: " + rerun(shard));
      continue;
    }
    for (const json& row : section.at("rows")) rows[row.at("frame").get<int>()] = row;
  }
}

// Every per-frame file of `frames` in place: a regular file inside `dir`, reached through no
// link. The whole-run files (those an output lists for no frame) are merge's to write.
void verify_frame_files(const TrackPlan& plan, const std::vector<int>& frames,
                        std::vector<std::string>& problems) {
  const fs::path& dir = plan.config.output.dir;
  for (const auto& output : plan.outputs.outputs) {
    const std::vector<fs::path> whole = output->files({});
    const std::set<fs::path> assembled(whole.begin(), whole.end());
    for (int f : frames)
      for (const fs::path& file : output->files({f})) {
        if (assembled.count(file)) continue;
        const std::string relative = file.lexically_relative(dir).string();
        std::string problem = confinement_problem(dir, relative);
        std::error_code ec;
        if (problem.empty() && !fs::is_regular_file(file, ec)) problem = "missing";
        if (!problem.empty())
          problems.push_back("frame " + std::to_string(f) + ": " + relative + ": " + problem);
      }
  }
}

}  // namespace

std::string shard_job(const fs::path& dir) {
  try {  // the sequence merge reports what is wrong, holding the folder's lock
    const std::vector<ShardReport> reports = read_shard_reports(dir);
    return reports.front().report.value("job", "") == "track" ? "track" : "";
  } catch (const Error&) {
    return "";
  }
}

TrackMergeResult merge_track_shards(const fs::path& output_dir) {
  const OutputLock lock = lock_output_folder(output_dir);
  const fs::path dir = fs::absolute(output_dir).lexically_normal();
  const std::vector<ShardReport> reports = read_shard_reports(dir);
  verify_same_job(dir, reports);
  const int count = reports.front().shard.count;

  TrackJobOptions config;
  read_options(reports.front().report.at("config"), config, dir);
  config.output.dir = dir;
  config.shard = ShardOptions{};
  const TrackPlan plan = plan_track_job(config);
  if (plan.outputs.source->report() != reports.front().report.at("input"))
    throw InputError("'" + dir.string() + "': the input changed since the shards ran: " +
                     first_difference(reports.front().report.at("input"),
                                      plan.outputs.source->report()) +
                     "; run every shard again");

  std::map<int, json> rows;
  std::vector<std::string> problems;
  collect_rows(reports, plan, count, rows, problems);
  std::vector<int> frames;
  for (const auto& [index, row] : rows) frames.push_back(index);
  verify_frame_files(plan, frames, problems);
  if (!problems.empty()) {
    std::string text = "'" + dir.string() + "': cannot merge " + std::to_string(count) +
                       " shards:";
    for (const std::string& p : problems) text += "\n  " + p;
    throw InputError(text + "\n(CONFIG: the config file the shards ran; then merge again: " +
                     "seqmassage merge " + output_dir.string() + ")");
  }

  TrackMergeResult out;
  out.shards = count;
  TrackResult result;
  result.warnings = plan.warnings;
  std::vector<FrameSummary> summaries;
  FinishedFrames done;
  for (const auto& [index, entry] : rows) {
    TrackRow row;
    try {
      row = track_row_from_json(entry);
      summaries.push_back(frame_summary_from_json(entry.at("summary")));
      append_record_rows(done.record_rows, entry.at("record_rows").get<RecordRows>());
    } catch (const std::exception& e) {
      throw InputError("'" + dir.string() + "': frame " + std::to_string(index) +
                       " in its shard's report: " + e.what());
    }
    if (row.status == TrackStatus::Lost)
      result.warnings.push_back(frame_label(index, row.file, std::nullopt) +
                                " lost (written as its best attempt): " + row.beyond);
    result.lost += row.status == TrackStatus::Lost;
    result.recovered += row.status == TrackStatus::Recovered;
    done.frames.push_back(index);
    done.names.push_back(plan.outputs.source->name(index));
    result.frames.push_back(std::move(row));
  }
  for (int i = 1; i < count; ++i)
    if (const std::vector<int> block = shard_frames(plan.selected, {i, count}); !block.empty())
      out.seams.push_back({block.front(), i});

  remove_stale_temporaries(dir);
  for (const auto& output : plan.outputs.outputs)
    for (const fs::path& folder : output->folders()) remove_stale_temporaries(folder);
  done.summaries = &summaries;
  done.warnings = &result.warnings;
  for (const auto& output : plan.outputs.outputs) {
    OutputFinish finished = output->finish(done);
    for (std::string& w : finished.warnings) result.warnings.push_back(std::move(w));
    for (std::string& file : finished.written) out.written.push_back(std::move(file));
  }
  for (const ShardReport& r : reports)
    if (r.report.contains("run")) result.seconds += r.report["run"].value("seconds", 0.0);

  json report = make_track_report(plan, result);
  json seams = json::array();
  for (const TrackSeam& seam : out.seams) {
    const TrackRow& row = result.frames[size_t(
        std::find(done.frames.begin(), done.frames.end(), seam.frame) - done.frames.begin())];
    seams.push_back({{"frame", seam.frame},
                     {"shard", seam.shard},
                     {"status", std::string(name_of(row.status, kTrackStatusNames))},
                     {"to_raw_mean", row.fit.to_raw_mean},
                     {"from_raw_mean", row.fit.from_raw_mean}});
  }
  report["merged"] = {{"shards", count}, {"seams", seams}};
  write_file_atomic(dir / "summary.csv", format_track_summary_csv(result.frames));
  write_file_atomic(dir / "report.json", report.dump(2) + "\n");
  out.written.insert(out.written.begin(), {"summary.csv", "report.json"});
  out.frames = std::move(result.frames);
  out.lost = result.lost;
  out.recovered = result.recovered;
  out.warnings = std::move(result.warnings);
  out.notices = lock.warnings();
  return out;
}

}  // namespace sm
