#include "pipeline/sequence/frame_summary.hpp"

namespace sm {

const char* status_name(FrameStatus status) {
  switch (status) {
    case FrameStatus::Optimized:
      return "optimized";
    case FrameStatus::Template:
      return "template";
    case FrameStatus::Failed:
      return "failed";
  }
  return "";
}

}  // namespace sm
