#include "pipeline/cluster/output_lock.hpp"
#include "pipeline/cluster/merge.hpp"

#include <map>
#include <regex>
#include <set>

#include "io/atomic_file.hpp"
#include "io/gltf/gltf_load.hpp"
#include "io/vertex_weights.hpp"
#include "io/options_json.hpp"
#include "core/errors.hpp"
#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/cluster/frame_record.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/sequence/shard.hpp"
#include "pipeline/sequence/frame_sources.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

std::string first_difference(const json& a, const json& b, const std::string& path) {
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

json job_config(const json& config) {
  json c = config;
  c.erase("threads");
  c.erase("frames_in_flight");
  if (c.contains("output")) c["output"].erase("dir");
  return c;
}

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

std::vector<ShardReport> read_shard_reports(const fs::path& dir) {
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
    if (std::string link = confinement_problem(dir, s.file); !link.empty())
      throw InputError("'" + (dir / s.file).string() + "': refusing to read it: " + link);
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

namespace {

// What merge works from, found and read by find_shards.
struct Shards {
  fs::path dir;
  std::vector<ShardReport> reports;  // by split, then index
  int count = 0;                     // N
  ReportHeader header;               // the first shard's
  SequenceJobOptions config;         // as the shards' reports resolved it
  std::map<int, std::string> names;  // every frame's name that is known
};

Shards find_shards(const fs::path& output_dir) {
  Shards s;
  s.dir = fs::absolute(output_dir).lexically_normal();
  s.reports = read_shard_reports(s.dir);
  s.count = s.reports.front().shard.count;
  s.header = report_header_from_json(s.reports.front().report);
  read_options(s.header.config, s.config, s.dir);
  for (const ShardReport& r : s.reports)
    for (const auto& [index, name] : r.frames) s.names[index] = name;
  return s;
}

// Why the config hash of shard report `r` is not the one of its config ("" if it is): its config
// and versions hashed again as frame_config_hash does (with the vertex weights its config names).
std::string config_hash_problem(const Shards& s, const ShardReport& r) {
  const ReportHeader h = report_header_from_json(r.report);
  std::string recomputed;
  try {
    SequenceJobOptions config;
    read_options(h.config, config, s.dir);
    if (!config.massage.vertex_weights_file.empty())
      config.massage.vertex_weights = read_vertex_weights(
          config.massage.vertex_weights_file, h.templ.value("vertices", 0), "the template");
    recomputed = frame_config_hash(config, h.versions);
  } catch (const Error& e) {
    return r.file + ": cannot hash its config again: " + e.what();
  }
  if (recomputed == h.config_hash) return "";
  return r.file + ": its hashes.config is not the hash of its config (the config, or the vertex "
                  "weights file it names, changed after the shard ran, or the report is not one "
                  "seqmassage wrote); run the shard again: seqmassage --shard " +
         format_shard(r.shard) + " --resume CONFIG";
}

// Throws InputError when a shard ran another build, config, template or input than the first, or
// when a report's config hash is not its config's.
void verify_same_job(const Shards& s) {
  const ShardReport& ref = s.reports.front();
  std::vector<std::string> problems;
  for (const ShardReport& r : s.reports)
    if (std::string problem = config_hash_problem(s, r); !problem.empty())
      problems.push_back(problem);
  for (const ShardReport& r : s.reports) {
    if (&r == &ref) continue;
    const ReportHeader h = report_header_from_json(r.report);
    const ReportHeader& header = s.header;
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
    if (!diff.empty()) problems.push_back(r.file + " ran " + diff + " than " + ref.file);
  }
  if (problems.empty()) return;
  std::string text = "'" + s.dir.string() + "': the shards are not of one job:";
  for (const std::string& p : problems) text += "\n  " + p;
  throw InputError(text + "\nrun the odd shards again with the config of the others");
}

// Every shard there, complete, with its block of the selection; every frame once. Returns the
// shard file of every frame; adds what is wrong to `problems` (and names from the input, when
// a shard is missing and the input can be listed).
void verify_blocks(Shards& s, const std::vector<int>& selected,
                   std::vector<std::string>& problems) {
  std::map<int, const ShardReport*> by_index;
  for (const ShardReport& r : s.reports) by_index[r.shard.index] = &r;
  std::map<int, std::string> owner;  // frame -> shard file
  for (int i = 0; i < s.count; ++i) {
    const ShardOptions shard{i, s.count};
    const std::vector<int> block = shard_frames(selected, shard);
    const auto it = by_index.find(i);
    const std::string rerun = "seqmassage --shard " + format_shard(shard) + " --resume CONFIG";
    if (it == by_index.end()) {
      if (s.names.size() < selected.size()) {
        try {
          const std::shared_ptr<const FrameSource> source = make_frame_source(s.config);
          for (int f : block) s.names[f] = source->name(f);
        } catch (const Error&) {  // the input is not reachable: indices only
        }
      }
      problems.push_back(
          shard_label(shard) + ": no " + report_file_name(shard) +
          (block.empty() ? " (it has no frames)" : "; missing " + describe_frames(block, s.names)) +
          "; run it: " + rerun);
      continue;
    }
    const ShardReport& r = *it->second;
    std::vector<int> listed;
    for (const auto& [index, name] : r.frames) listed.push_back(index);
    if (listed != block) {
      problems.push_back(r.file + ": its frames (" + describe_frames(listed, s.names) +
                         ") are not " + shard_label(shard) + " of the selection (" +
                         describe_frames(block, s.names) + ")");
      continue;
    }
    for (int f : listed) {
      const auto [at, fresh] = owner.emplace(f, r.file);
      if (!fresh)
        problems.push_back("frame " + std::to_string(f) + " is in " + at->second + " and " +
                           r.file);
    }
    if (!r.report.at("shard").value("complete", false))  // its missing frames are listed below
      problems.push_back(r.file + ": " + shard_label(shard) +
                         " was interrupted before its last frame; run it again: " + rerun);
  }
}

// Why frame `f`'s record cannot be merged, or "" (then `record` holds it). `tampered`: an
// output (or the record) is not what the shard wrote: changed, a link, or a path outside.
std::string record_problem(const Shards& s, int f, const std::string& name,
                           std::optional<FrameRecord>& record, bool& tampered) {
  tampered = false;
  const fs::path file = record_file(s.dir, name);
  if (std::string link = confinement_problem(s.dir, file.lexically_relative(s.dir).string());
      !link.empty()) {
    tampered = true;
    return link;
  }
  std::string problem;
  record = read_frame_record(file, &problem);
  if (!record) return problem;
  if (record->config_hash != s.header.config_hash) return "its record is of another config";
  if (record->template_hash != s.header.templ.value("hash", ""))
    return "its record is of another template";
  if (record->summary.frame != f || record->summary.file != name)
    return "its record is another frame's";
  // The content too, as --resume checks it: merge publishes these bytes.
  return check_recorded_outputs(*record, s.dir, true, &tampered);
}

// Every selected frame's record, of this job, with its outputs: their rows into `result`, their
// record rows into `rows`; what is wrong into `problems`.
void verify_records(const Shards& s, const std::vector<int>& selected,
                    MergeResult& result, RecordRows& rows,
                    std::vector<std::string>& problems) {
  std::vector<int> bad_frames;
  std::string first_bad;
  std::map<int, std::string> shard_of;  // frame -> its shard's report file
  for (const ShardReport& r : s.reports)
    for (const auto& [index, frame_name] : r.frames) shard_of[index] = r.file;
  int tampered_shown = 0;
  for (int f : selected) {
    const auto name = s.names.find(f);
    if (name == s.names.end()) continue;  // in a missing shard, reported already
    std::optional<FrameRecord> r;
    bool tampered = false;
    if (std::string problem = record_problem(s, f, name->second, r, tampered); !problem.empty()) {
      if (tampered && tampered_shown++ < 20)
        problems.push_back(shard_of[f] + ": " + frame_label(f, name->second, std::nullopt) +
                           ": refusing to publish " + problem);
      bad_frames.push_back(f);
      if (first_bad.empty())
        first_bad = frame_label(f, name->second, std::nullopt) + ": " + problem;
      continue;
    }
    result.frames.push_back(r->summary);
    append_record_rows(rows, r->record_rows);
  }
  if (bad_frames.empty()) return;
  const std::set<int> bad(bad_frames.begin(), bad_frames.end());
  std::set<int> redo;  // the shards whose blocks hold a bad frame
  for (int i = 0; i < s.count; ++i)
    for (int f : shard_frames(selected, {i, s.count}))
      if (bad.count(f)) redo.insert(i);
  std::string rerun;
  for (int i : redo)
    rerun += (rerun.empty() ? "" : "; ") + std::string("seqmassage --shard ") +
             format_shard({i, s.count}) + " --resume CONFIG";
  problems.push_back("missing or incomplete frames: " + describe_frames(bad_frames, s.names) +
                     " (first: " + first_bad + "); run " +
                     (redo.size() == 1 ? "its shard" : "their shards") + " again: " + rerun);
}

// The whole run's outputs: every output's finish over the merged frames, summary.csv and
// report.json.
void assemble(const Shards& s, const RecordRows& rows, MergeResult& result) {
  const SequenceJobOptions& config = s.config;
  result.warnings = s.header.warnings;
  for (const FrameSummary& f : result.frames) {
    append_frame_warnings(f, config.output.on_failure, result.warnings);
    result.failed += f.status == FrameStatus::Failed;
  }
  SequenceJobOptions whole = config;  // the shards' config: "shard" is the whole run's
  whole.output.dir = s.dir;
  const auto gltf = [&]() -> std::shared_ptr<const GltfSequence> {
    if (!whole.input.gltf) return nullptr;
    return std::make_shared<const GltfSequence>(load_gltf_sequence(*whole.input.gltf));
  };
  const std::vector<std::shared_ptr<FrameOutput>> outputs =
      make_frame_outputs({whole, nullptr, gltf});
  for (const char* sub : {".", "records"}) remove_stale_temporaries(s.dir / sub);
  for (const auto& output : outputs)
    for (const fs::path& folder : output->folders()) remove_stale_temporaries(folder);
  FinishedFrames done;
  done.record_rows = rows;
  done.summaries = &result.frames;
  done.warnings = &result.warnings;
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
    for (const ShardReport& r : s.reports)
      seconds.push_back(r.report.contains("run") ? r.report["run"].value("seconds", 0.0) : 0.0);
    run = {{"merged_shards", s.count}, {"shard_seconds", seconds}};
  }
  write_file_atomic(s.dir / "summary.csv",
                    format_summary_csv(result.frames, config.output.timings));
  write_file_atomic(
      s.dir / "report.json",
      make_report(s.header, result.frames, result.warnings, false, run).dump(2) + "\n");
  result.written.insert(result.written.begin(), {"summary.csv", "report.json"});
}

}  // namespace

MergeResult merge_shards(const fs::path& output_dir) {
  std::error_code ec;
  if (!fs::is_directory(output_dir, ec))
    throw IoError("cannot open folder '" + output_dir.string() +
                  "': " + (fs::exists(output_dir, ec) ? "not a folder" : "no such folder"));
  // The folder's exclusive lock: no shard (nor a whole run) writes while merge reads and writes.
  const OutputLock lock = lock_output_folder(output_dir);
  Shards shards = find_shards(output_dir);
  verify_same_job(shards);
  const std::vector<int> selected =
      select_frames(shards.config.input.range, shards.header.frames_listed);
  std::vector<std::string> problems;
  verify_blocks(shards, selected, problems);
  MergeResult result;
  result.shards = shards.count;
  RecordRows rows;  // the records' rows (iterations.csv's), in frame order
  verify_records(shards, selected, result, rows, problems);
  if (!problems.empty()) {
    std::string text = "'" + shards.dir.string() + "': cannot merge " +
                       std::to_string(shards.count) + " shards:";
    for (const std::string& p : problems) text += "\n  " + p;
    throw InputError(text + "\n(CONFIG: the config file the shards ran; then merge again: " +
                     "seqmassage merge " + output_dir.string() + ")");
  }
  assemble(shards, rows, result);
  result.notices = lock.warnings();
  return result;
}

}  // namespace sm
