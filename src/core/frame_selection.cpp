#include "core/frame_selection.hpp"

#include "core/errors.hpp"

namespace sm {

FrameRange parse_frame_range(std::string_view text, std::string_view what) {
  const std::string name(what);
  const auto fail = [&](const std::string& why) {
    throw ConfigError(name + ": " + why + ", got \"" + std::string(text) + "\"");
  };
  const auto bad = [&]() {
    fail("expected A:B[:STEP] (frame indices from A to before B, by STEP; B may be empty)");
  };
  std::vector<std::string> parts;
  size_t begin = 0;
  while (true) {
    const size_t colon = text.find(':', begin);
    parts.emplace_back(text.substr(begin, colon == std::string_view::npos ? colon : colon - begin));
    if (colon == std::string_view::npos) break;
    begin = colon + 1;
  }
  if (parts.size() > 3) bad();
  auto number = [&](const std::string& s) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) bad();
    return std::stoi(s);
  };
  FrameRange r;
  if (parts.size() == 1) {  // a single frame
    r.start = number(parts[0]);
    r.stop = r.start + 1;
    return r;
  }
  r.start = parts[0].empty() ? 0 : number(parts[0]);
  if (!parts[1].empty()) r.stop = number(parts[1]);
  if (parts.size() == 3) r.step = number(parts[2]);
  if (r.step < 1) fail("STEP must be >= 1");
  if (r.stop && *r.stop < r.start) fail("B must be >= A");
  return r;
}

std::string format_frame_range(const FrameRange& range) {
  return std::to_string(range.start) + ":" + (range.stop ? std::to_string(*range.stop) : "") + ":" +
         std::to_string(range.step);
}

}  // namespace sm
