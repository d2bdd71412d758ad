#pragma once
/// Which frames of a sequence: a range [start, stop) by step, as a Python slice ("A:B[:STEP]"),
/// and a selection of frames for an optional output ("all", a list, or a range).
#include <algorithm>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/options_table.hpp"

namespace sm {

/// Frames [start, stop) by step, in the natural order of the input frames.
struct FrameRange {
  int start = 0;            ///< >= 0
  std::optional<int> stop;  ///< one past the last frame, >= start; empty = to the end
  int step = 1;             ///< >= 1
};

/// Frames chosen for an optional output, by their index in the full list of input frames (like
/// template.frame): "all", an array of indices, or a range "A:B[:STEP]" (B may be empty: to the
/// end). Only frames the run processes are written.
struct FrameSelection {
  enum class Kind { All, List, Range };
  Kind kind = Kind::All;
  std::vector<int> list;    ///< Kind::List: sorted, without repeats (may be empty: no frame)
  int start = 0;            ///< Kind::Range: first frame
  std::optional<int> stop;  ///< Kind::Range: one past the last frame; empty = to the end
  int step = 1;             ///< Kind::Range: >= 1

  static FrameSelection none() { return {Kind::List, {}, 0, std::nullopt, 1}; }
  bool contains(int frame) const;
};

/// "input.range" of the sequence job; "start" comes first: "stop" is checked against it.
template <>
inline const Fields<FrameRange>& fields_of<FrameRange>() {
  using O = FrameRange;
  static const Fields<O> fields = {
      field<&O::start>("start", at_least(0), "first frame (below the number of frames)"),
      field<&O::stop>("stop", at_least_key("start"),
                      "one past the last frame (a stop beyond the end is the end); `null`: to the "
                      "end"),
      field<&O::step>("step", at_least(1), "step"),
  };
  return fields;
}

/// Parses "A:B[:STEP]" (B may be empty: to the end; "N" alone is N:N+1) into a range. Throws
/// ConfigError naming `what` (e.g. "--frames").
FrameRange parse_frame_range(std::string_view text, std::string_view what);

/// The range as "A:B:STEP" ("A::STEP" without a stop).
std::string format_frame_range(const FrameRange& range);

inline bool FrameSelection::contains(int frame) const {
  switch (kind) {
    case Kind::All:
      return true;
    case Kind::List:
      return std::binary_search(list.begin(), list.end(), frame);
    case Kind::Range:
      return frame >= start && (!stop || frame < *stop) && (frame - start) % step == 0;
  }
  return false;
}

}  // namespace sm
