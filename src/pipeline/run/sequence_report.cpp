#include "pipeline/run/sequence_report.hpp"

#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/run/frame_processor.hpp"
#include "pipeline/sequence/frame_source.hpp"
#include "pipeline/sequence/shard.hpp"

namespace sm {
using json = nlohmann::json;

ReportHeader report_header(const SequencePlan& plan) {
  const SequenceJobOptions& c = plan.config;
  ReportHeader h;
  h.versions = version_info();
  SequenceJobOptions job = c;
  job.shard = ShardOptions{};
  job.resume = false;
  h.config = to_json(job);
  h.input = plan.source->report();
  h.templ = {{"source", plan.template_source},
             {"vertices", plan.templ.num_vertices()},
             {"triangles", plan.templ.num_triangles()},
             {"weight_fallback_vertices", plan.processor->massager().weights().fallback_vertices},
             {"hash", plan.template_hash}};
  // "distortion" is null when that output is off (report.json has always listed it).
  h.outputs = {{"dir", c.output.dir.string()},
               {"distortion", nullptr},
               {"records", "records/"},
               {"summary", "summary.csv"}};
  for (const auto& output : plan.outputs) h.outputs.update(output->report());
  h.frames_listed = plan.source->size();
  h.frames_selected = static_cast<int>(plan.selected.size());
  h.ground_truth = plan.source->ground_truth_dir().string();
  h.config_hash = plan.config_hash;
  h.warnings = plan.warnings;
  return h;
}

std::vector<std::string> run_output_names(const SequencePlan& plan) {
  const SequenceJobOptions& c = plan.config;
  std::vector<std::string> names = result_names(plan.outputs, {"records/"});
  names.push_back(summary_file_name(c.shard));
  names.push_back(report_file_name(c.shard));
  return names;
}

json make_report(const SequencePlan& plan, const SequenceResult& result) {
  const SequenceJobOptions& c = plan.config;
  const ReportHeader header = report_header(plan);
  json run;
  if (c.output.timings) {
    const size_t processed = result.frames.size() - size_t(result.resumed);
    run = {{"threads", plan.threads},
           {"frames_in_flight", plan.frames_in_flight},
           {"seconds", result.seconds},
           {"seconds_outputs_finish", result.seconds_finish},
           {"frames_processed", processed},
           {"frames_resumed", result.resumed},
           {"frames_per_second", result.seconds > 0 ? processed / result.seconds : 0.0}};
  }
  json r = make_report(header, result.frames, result.warnings, result.interrupted, run);
  if (c.shard.sharded()) {
    json frames = json::array();
    for (int index : plan.run_frames)
      frames.push_back({{"frame", index}, {"file", plan.source->name(index)}});
    r["outputs"]["summary"] = summary_file_name(c.shard);
    r["shard"] = {
        {"index", c.shard.index},
        {"count", c.shard.count},
        {"complete", !result.interrupted && result.frames.size() == plan.run_frames.size()},
        {"frames", frames},
        {"plan_warnings", plan.warnings}};
  }
  return r;
}

}  // namespace sm
