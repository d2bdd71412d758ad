#pragma once
/// The lines that the command line prints about a run (without the "seqmassage: " prefix): its
/// start, every frame, a failed frame, a resume, its end, and the single-mesh jobs' start and end.
#include <string>

#include "massage/massage_options.hpp"
#include "pipeline/sequence/sequence_types.hpp"

namespace sm {

/// `x` with `digits` decimals ("%.*f").
std::string fixed_text(double x, int digits);

/// A duration as M:SS or H:MM:SS; "--:--" when negative, NaN or 100 hours and more.
std::string clock_text(double seconds);

/// "12 frames (shard 2/3 of 36 selected), template frame 0 (a.obj), 4 threads, resuming".
std::string run_start_text(const SequencePlan& plan);

/// "frame 3/12 a.obj: optimized, mean shear 0.1 -> 0.01, 8 iterations, 2.00 frames/s, ETA 0:05"
/// after `done` of `total` frames in `elapsed` seconds.
std::string frame_progress_text(const FrameSummary& f, int done, int total, double elapsed);

/// The bar of a terminal: "[#####.....] 3/12 frames  2.00 frames/s  ETA 0:05".
std::string progress_bar_text(int done, int total, double elapsed);

/// "frame 3 (a.obj) failed, written unchanged: <reason>" ("not written" with on_failure "skip").
std::string frame_failure_text(const FrameSummary& f, OnFailure on_failure);

/// "resume: 8 frames kept from earlier runs, 4 processed (3 changed input, 1 no record)".
std::string resume_text(const SequenceResult& result);

/// "12 frames in 3.4 s (0 failed), mean shear 0.2777 -> 0.0177".
std::string run_end_text(const SequenceResult& result);

/// "mean_value weights, 15 iterations, mu auto, samples vertices, solver iterative" (the dry
/// runs' "massage:" line).
std::string massage_text(const MassageOptions& options);

}  // namespace sm
