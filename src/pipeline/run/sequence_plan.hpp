#pragma once
/// Planning a sequence job: every input read and checked, nothing written (plan_sequence_job),
/// and the plan as text for --dry-run (describe_plan). The plan itself is in sequence_types.hpp.
#include <string>

#include "pipeline/sequence/sequence_options.hpp"
#include "pipeline/sequence/sequence_types.hpp"

namespace sm {

/// Checks the config and every input before anything runs: lists the frames (or loads and welds
/// the glTF), selects the run's frames (input.range, then config.shard), reads every one of them
/// (in parallel, in a bounded way) and compares its vertex count and faces with the template's,
/// builds the template's Massager, and refuses an output folder that would overwrite an input.
/// Throws ConfigError, InputError (naming the frame and the counts, or the glTF file and element)
/// or IoError. Writes nothing.
SequencePlan plan_sequence_job(const SequenceJobOptions& config);

/// What a run of `plan` would do, several lines of text (for --dry-run).
std::string describe_plan(const SequencePlan& plan);

}  // namespace sm
