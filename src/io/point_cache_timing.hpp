#pragma once
/// The rule a PC2 header's timing (start frame, sample rate) obeys, read or written.
#include <string>

namespace sm {

/// Why a PC2 header's timing is refused, or "" if it is not: a start frame or sample rate that is
/// not finite, a sample rate not above 0, or a frame number start + k × rate (k below `samples`)
/// beyond 1e18 in magnitude (the coordinate limit). A cache written from a selection of such
/// frames (start: a selected frame's number; rate: the step between two) passes again, so every
/// header of a cache read and written is finite in float32 and readable.
std::string pc2_timing_problem(float start, float sample_rate, int samples);

}  // namespace sm
