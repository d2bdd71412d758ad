// The registry of per-frame outputs (frame_output.hpp): one line per output, in the order of
// the dry run, the frame records, --help and the results line.
#include <algorithm>

#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/outputs/output_checker.hpp"
#include "pipeline/outputs/output_colored.hpp"
#include "pipeline/outputs/output_displacement.hpp"
#include "pipeline/outputs/output_distortion.hpp"
#include "pipeline/outputs/output_frames.hpp"
#include "pipeline/outputs/output_html.hpp"
#include "pipeline/outputs/output_iterations.hpp"
#include "pipeline/outputs/output_point_cache.hpp"

namespace sm {

const std::vector<OutputEntry>& output_registry() {
  static const std::vector<OutputEntry> registry = {
      output<ObjFramesOutput>(),
      output<GlbFramesOutput>(),
      output<PointCacheOutput>(),
      output<DistortionCsvOutput>(),
      output<DisplacementCsvOutput>(),
      output<ColoredPlyOutput>(),
      output<CheckerObjOutput>(),
      output<IterationsCsvOutput>(),
      output<HtmlReportOutput>(),  // last: its page lists the others' warnings
  };
  return registry;
}

std::vector<std::shared_ptr<FrameOutput>> make_frame_outputs(const OutputContext& context) {
  std::vector<std::shared_ptr<FrameOutput>> outputs;
  for (const OutputEntry& entry : output_registry())
    if (entry.enabled(context.config)) {
      outputs.push_back(entry.make(context));
      outputs.back()->record_key_ = entry.record_key;
    }
  return outputs;
}

std::vector<std::string> record_row_keys() {
  std::vector<std::string> keys;
  for (const OutputEntry& entry : output_registry())
    if (entry.record_key) keys.push_back(entry.record_key);
  return keys;
}

void append_record_rows(RecordRows& rows, const RecordRows& more) {
  for (const auto& [key, text] : more) rows[key] += text;
}

void FrameOutput::add_record_rows(RecordRows& rows, const OutputFrame& part) const {
  if (record_key_) rows[record_key_] += part.record_rows;
}

std::vector<std::string> result_names(const std::vector<std::shared_ptr<FrameOutput>>& outputs,
                                      const std::vector<std::string>& middle) {
  std::vector<std::string> names, tables;
  for (const auto& output : outputs) {
    ResultNames r = output->results();
    names.insert(names.end(), r.before_records.begin(), r.before_records.end());
    tables.insert(tables.end(), r.after_records.begin(), r.after_records.end());
  }
  names.insert(names.end(), middle.begin(), middle.end());
  names.insert(names.end(), tables.begin(), tables.end());
  return names;
}

std::string outputs_help() {
  std::string text;
  for (const OutputEntry& entry : output_registry()) text += entry.help();
  return text;
}

std::string frames_text(int n) {
  return std::to_string(n) + (n == 1 ? " frame" : " frames");
}

int count_in(const FrameSelection& selection, const std::vector<int>& frames) {
  int n = 0;
  for (int i : frames) n += selection.contains(i);
  return n;
}

std::vector<std::string> unlisted_frames(const FrameSelection& selection,
                                         const std::vector<int>& selected,
                                         const std::string& key) {
  if (selection.kind != FrameSelection::Kind::List) return {};
  std::string missing;
  for (int i : selection.list)
    if (!std::binary_search(selected.begin(), selected.end(), i))
      missing += (missing.empty() ? "" : ", ") + std::to_string(i);
  if (missing.empty()) return {};
  return {key + ": frame" + (missing.find(',') == std::string::npos ? " " : "s ") + missing +
          " not processed by this run (see input.range and --frames)"};
}

}  // namespace sm
