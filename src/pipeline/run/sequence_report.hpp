#pragma once
/// report.json of a planned sequence run: its header from the plan and its outputs, the names
/// of what it writes, the report with its times and shard section (report/report.hpp writes
/// the parts that need no plan, which merge reuses).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/report/report.hpp"
#include "pipeline/sequence/sequence_types.hpp"

namespace sm {

/// The header of a plan's report.
ReportHeader report_header(const SequencePlan& plan);

/// What a run writes, relative to output.dir, for the command line's results line: every
/// output's folders (FrameOutput::results), records/, the outputs' whole-run tables, summary.csv
/// and report.json (the last two shard-named for a shard).
std::vector<std::string> run_output_names(const SequencePlan& plan);

/// The report of a run: make_report of the plan's header and the result's frames, with the run's
/// times (config.output.timings), and for a shard its "shard" section (index, count, its frames,
/// whether it is complete, the plan's warnings), from which `seqmassage merge` works.
nlohmann::json make_report(const SequencePlan& plan, const SequenceResult& result);

}  // namespace sm
