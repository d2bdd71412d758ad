#include "pipeline/merge.hpp"

#include <map>
#include <regex>
#include <set>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/options_json.hpp"
#include "mesh/errors.hpp"
#include "pipeline/frame_record.hpp"
#include "io/gltf_load.hpp"
#include "pipeline/frame_output.hpp"
#include "pipeline/report.hpp"
#include "pipeline/shard.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

struct ShardReport {
  ShardOptions shard;
  std::string file;  // report.shard-I-of-N.json
  json report;
  std::vector<std::pair<int, std::string>> frames;  // (index, name) in order
};

// The first JSON path at which `a` and `b` differ, with both values ("" if equal).
std::string first_difference(const json& a, const json& b, const std::string& path = "") {
  if (a == b) return "";
  if (a.is_object() && b.is_object()) {
    std::set<std::string> keys;
    for (const auto& item : a.items()) keys.insert(item.key());
    for (const auto& item : b.items()) keys.insert(item.key());
    for (const std::string& key : keys) {
      const std::string child = path.empty() ? key : path + "." + key;
      if (!a.contains(key) || !b.contains(key)) return child + " (present in one only)";
      if (std::string d = first_difference(a[key], b[key], child); !d.empty()) return d;
    }
  }
  std::string left = a.dump(), right = b.dump();
  if (left.size() > 60) left = left.substr(0, 57) + "...";
  if (right.size() > 60) right = right.substr(0, 57) + "...";
  return (path.empty() ? std::string("the top level") : path) + " (" + left + " vs " + right + ")";
}

// The job's config as shards must agree on it: threads, frames_in_flight and the output
// folder's path (mounted elsewhere on another node) may differ.
json job_config(const json& config) {
  json c = config;
  c.erase("threads");
  c.erase("frames_in_flight");
  if (c.contains("output")) c["output"].erase("dir");
  return c;
}

// "frames 5 to 9" / "frame 5", by contiguous runs of indices, then names where known.
std::string describe_frames(const std::vector<int>& frames,
                            const std::map<int, std::string>& names) {
  std::string text;
  size_t shown = 0;
  for (size_t k = 0; k < frames.size();) {
    size_t e = k;
    while (e + 1 < frames.size() && frames[e + 1] == frames[e] + 1) ++e;
    if (!text.empty()) text += ", ";
    const auto name = [&](int i) {
      const auto it = names.find(i);
      return it == names.end() ? std::string() : " (" + it->second + ")";
    };
    if (e == k)
      text += "frame " + std::to_string(frames[k]) + name(frames[k]);
    else
      text += "frames " + std::to_string(frames[k]) + name(frames[k]) + " to " +
              std::to_string(frames[e]) + name(frames[e]);
    k = e + 1;
    if (++shown == 20 && k < frames.size()) {
      text += ", ... (" + std::to_string(frames.size() - k) + " more)";
      break;
    }
  }
  return text;
}

std::vector<ShardReport> find_shard_reports(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw IoError("cannot open folder '" + dir.string() +
                  "': " + (fs::exists(dir, ec) ? "not a folder" : "no such folder"));
  const std::regex pattern(R"(report\.shard-(\d{1,6})-of-(\d{1,6})\.json)");
  std::vector<ShardReport> found;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    std::smatch m;
    if (!std::regex_match(name, m, pattern)) continue;
    ShardReport s;
    s.shard.index = std::stoi(m[1]);
    s.shard.count = std::stoi(m[2]);
    s.file = name;
    found.push_back(std::move(s));
  }
  std::sort(found.begin(), found.end(), [](const ShardReport& a, const ShardReport& b) {
    return std::make_pair(a.shard.count, a.shard.index) <
           std::make_pair(b.shard.count, b.shard.index);
  });
  if (found.empty()) {
    const bool single = fs::exists(dir / "report.json", ec);
    throw InputError("'" + dir.string() + "': no shard reports (report.shard-I-of-N.json)" +
                     (single ? "; its report.json is a whole run's, there is nothing to merge"
                             : "; run the shards with --shard I/N first"));
  }
  std::set<int> counts;
  for (const ShardReport& s : found) counts.insert(s.shard.count);
  if (counts.size() > 1) {
    std::string list;
    for (const ShardReport& s : found) list += (list.empty() ? "" : ", ") + s.file;
    throw InputError("'" + dir.string() + "': shard reports of different splits (" + list +
                     "); remove those of the split you do not want to merge");
  }
  for (ShardReport& s : found) {
    try {
      s.report = json::parse(read_file(dir / s.file));
      const json& section = s.report.at("shard");
      if (section.at("index").get<int>() != s.shard.index ||
          section.at("count").get<int>() != s.shard.count)
        throw InputError("its \"shard\" section says " +
                         std::to_string(section.at("index").get<int>()) + "/" +
                         std::to_string(section.at("count").get<int>()));
      for (const json& f : section.at("frames"))
        s.frames.emplace_back(f.at("frame").get<int>(), f.at("file").get<std::string>());
    } catch (const IoError&) {
      throw;
    } catch (const std::exception& e) {
      throw InputError("'" + (dir / s.file).string() + "': not a shard report: " + e.what());
    }
  }
  return found;
}

}  // namespace

MergeResult merge_shards(const fs::path& output_dir) {
  const fs::path dir = fs::absolute(output_dir).lexically_normal();
  std::vector<ShardReport> shards = find_shard_reports(dir);
  const int N = shards.front().shard.count;
  const ShardReport& ref = shards.front();
  const ReportHeader header = report_header_from_json(ref.report);
  SequenceJobOptions config;  // as the shards' reports resolved it (their configs were checked)
  read_options(header.config, config, dir);
  std::vector<std::string> problems;

  // Names of every frame, for the messages (from the shards, else from the input if it can be
  // listed; indices alone otherwise).
  std::map<int, std::string> names;
  for (const ShardReport& s : shards)
    for (const auto& [index, name] : s.frames) names[index] = name;
  std::shared_ptr<const FrameSource> source;
  const auto input_source = [&]() -> const FrameSource* {
    if (!source) source = make_frame_source(config);
    return source.get();
  };

  // The same job in every shard.
  for (const ShardReport& s : shards) {
    if (&s == &ref) continue;
    const ReportHeader h = report_header_from_json(s.report);
    std::string diff;
    if (h.versions != header.versions)
      diff = "another seqmassage build: " + first_difference(header.versions, h.versions);
    else if (h.config_hash != header.config_hash ||
             job_config(h.config) != job_config(header.config))
      diff = "another config: " + first_difference(job_config(header.config), job_config(h.config));
    else if (h.templ.value("hash", "") != header.templ.value("hash", ""))
      diff = "another template (its hash differs)";
    else if (h.input != header.input || h.frames_listed != header.frames_listed)
      diff = "another input: " + first_difference(header.input, h.input);
    if (!diff.empty()) problems.push_back(s.file + " ran " + diff + " than " + ref.file);
  }
  if (!problems.empty()) {
    std::string text = "'" + dir.string() + "': the shards are not of one job:";
    for (const std::string& p : problems) text += "\n  " + p;
    throw InputError(text + "\nrun the odd shards again with the config of the others");
  }

  // Every shard, complete, with its block of the selection; every frame once.
  const std::vector<int> selected = select_frames(config.input.range, header.frames_listed);
  std::map<int, const ShardReport*> by_index;
  for (const ShardReport& s : shards) by_index[s.shard.index] = &s;
  std::map<int, std::string> owner;  // frame -> shard file
  for (int i = 0; i < N; ++i) {
    const ShardOptions shard{i, N};
    const std::vector<int> block = shard_frames(selected, shard);
    const auto it = by_index.find(i);
    const std::string rerun = "seqmassage --shard " + format_shard(shard) + " --resume CONFIG";
    if (it == by_index.end()) {
      if (names.size() < selected.size()) {
        try {
          for (int f : block) names[f] = input_source()->name(f);
        } catch (const Error&) {  // the input is not reachable: indices only
        }
      }
      problems.push_back(
          shard_label(shard) + ": no " + report_file_name(shard) +
          (block.empty() ? " (it has no frames)" : "; missing " + describe_frames(block, names)) +
          "; run it: " + rerun);
      continue;
    }
    const ShardReport& s = *it->second;
    std::vector<int> listed;
    for (const auto& [index, name] : s.frames) listed.push_back(index);
    if (listed != block) {
      problems.push_back(s.file + ": its frames (" + describe_frames(listed, names) + ") are not " +
                         shard_label(shard) + " of the selection (" +
                         describe_frames(block, names) + ")");
      continue;
    }
    for (int f : listed) {
      const auto [at, fresh] = owner.emplace(f, s.file);
      if (!fresh)
        problems.push_back("frame " + std::to_string(f) + " is in " + at->second + " and " +
                           s.file);
    }
    if (!s.report.at("shard").value("complete", false))  // its missing frames are listed below
      problems.push_back(s.file + ": " + shard_label(shard) +
                         " was interrupted before its last frame; run it again: " + rerun);
  }

  // Every frame's record, of this job, with its outputs.
  MergeResult result;
  result.shards = N;
  std::string iteration_rows;  // the records' iterations.csv rows, in frame order
  std::vector<int> bad_frames;
  std::string first_bad;
  for (int f : selected) {
    const auto name = names.find(f);
    if (name == names.end()) continue;  // in a missing shard, reported above
    std::string problem;
    const std::optional<FrameRecord> r =
        read_frame_record(record_file(dir, name->second), &problem);
    if (r) {
      if (r->config_hash != header.config_hash)
        problem = "its record is of another config";
      else if (r->template_hash != header.templ.value("hash", ""))
        problem = "its record is of another template";
      else if (r->summary.frame != f || r->summary.file != name->second)
        problem = "its record is another frame's";
      else
        problem = check_recorded_outputs(*r, dir, false);
    }
    if (!problem.empty()) {
      bad_frames.push_back(f);
      if (first_bad.empty())
        first_bad = frame_label(f, name->second, std::nullopt) + ": " + problem;
      continue;
    }
    result.frames.push_back(r->summary);
    iteration_rows += r->iterations_csv;
  }
  if (!bad_frames.empty()) {
    std::set<std::string> files;
    for (int f : bad_frames) files.insert(owner.count(f) ? owner[f] : "?");
    std::string rerun;
    for (const std::string& file : files) rerun += (rerun.empty() ? "" : ", ") + file;
    problems.push_back("missing or incomplete frames: " + describe_frames(bad_frames, names) +
                       " (first: " + first_bad + "); run their shards again with --resume (" +
                       rerun + ")");
  }
  if (!problems.empty()) {
    std::string text = "'" + dir.string() + "': cannot merge " + std::to_string(N) + " shards:";
    for (const std::string& p : problems) text += "\n  " + p;
    throw InputError(text);
  }

  // The whole run's outputs.
  result.warnings = header.warnings;
  for (const FrameSummary& f : result.frames) {
    append_frame_warnings(f, config.output.on_failure, result.warnings);
    result.failed += f.status == FrameStatus::Failed;
  }
  SequenceJobOptions whole = config;  // the shards' config: "shard" is the whole run's
  whole.output.dir = dir;
  const auto gltf = [&]() -> std::shared_ptr<const GltfSequence> {
    if (!whole.input.gltf) return nullptr;
    return std::make_shared<const GltfSequence>(load_gltf_sequence(*whole.input.gltf));
  };
  const std::vector<std::shared_ptr<FrameOutput>> outputs =
      make_frame_outputs({whole, nullptr, gltf});
  for (const char* sub : {".", "records"}) remove_stale_temporaries(dir / sub);
  for (const auto& output : outputs)
    for (const fs::path& folder : output->folders()) remove_stale_temporaries(folder);
  FinishedFrames done;
  done.record_rows = iteration_rows;
  for (const FrameSummary& f : result.frames)
    if (!(f.status == FrameStatus::Failed && config.output.on_failure == OnFailure::Skip)) {
      done.frames.push_back(f.frame);
      done.names.push_back(f.file);
    }
  for (const auto& output : outputs) {
    OutputFinish finished = output->finish(done);
    for (std::string& w : finished.warnings) result.warnings.push_back(std::move(w));
    for (std::string& file : finished.written) result.written.push_back(std::move(file));
  }
  json run;
  if (config.output.timings) {
    json seconds = json::array();
    for (const ShardReport& s : shards)
      seconds.push_back(s.report.contains("run") ? s.report["run"].value("seconds", 0.0) : 0.0);
    run = {{"merged_shards", N}, {"shard_seconds", seconds}};
  }
  write_file_atomic(dir / "summary.csv", format_summary_csv(result.frames, config.output.timings));
  write_file_atomic(dir / "report.json",
                    make_report(header, result.frames, result.warnings, false, run).dump(2) + "\n");
  result.written.insert(result.written.begin(), {"summary.csv", "report.json"});
  return result;
}

}  // namespace sm
