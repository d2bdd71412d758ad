#pragma once
/// Wall-clock time of the stages that results and benchmarks report: the steady clock and the
/// seconds elapsed since a time point on it.
#include <chrono>

namespace sm {

using Clock = std::chrono::steady_clock;

/// Seconds from `t0` to now.
inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace sm
