#pragma once
/// The sequence job (paper §3.1): every frame of a mesh sequence is massaged towards the triangle
/// shapes of a template frame while it stays on its own surface, streamed through a bounded TBB
/// pipeline (read in order → decode, optimize, measure and encode in parallel → write in order)
/// from a FrameSource (OBJ folder, synthetic, glTF, point cache) to the per-frame outputs
/// (frame_output.hpp).
#include <string>

#include "pipeline/run/sequence_plan.hpp"  // plan_sequence_job, then run_sequence_job
#include "pipeline/sequence/sequence_types.hpp"

namespace sm {

/// Runs the job: takes the output folder's lock (lock_output_folder: IoError if another run
/// holds it), writes the synthetic input (if any), then per frame frames/<name>.obj (or
/// positions/<name>.bin, assembled into sequence.glb, or sequence.pc2 / .mdd and rest.obj, at the
/// end), distortion/<name>.csv (if asked)
/// and its record records/<name>.json, then summary.csv and report.json (named by shard for a
/// shard) under config.output.dir, each file atomically. With config.resume, a frame whose record
/// is current (same config hash, template hash and input hash; outputs present with their size
/// and SHA-256) is not processed again: its row comes from the record. A frame's numerical failure
/// (optimizer failure, non-finite positions, more folded triangles than checks allow) is recorded
/// in the result, not thrown. Same plan, same output bytes (apart from timings), whatever the
/// number of threads, interruptions and resumes.
SequenceResult run_sequence_job(const SequencePlan& plan, const RunHooks& hooks = {});

}  // namespace sm
