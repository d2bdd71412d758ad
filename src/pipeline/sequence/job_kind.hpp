#pragma once
/// The kinds of job a config names by its "job" key.
#include <string>

#include "core/enum_names.hpp"

namespace sm {

enum class JobKind {
  Sequence,    ///< "sequence": correct the texture swimming of a mesh sequence (paper §3.1)
  Remesh,      ///< "remesh": bring a remesh closer to its source surface (paper §3.3)
  Crossparam,  ///< "crossparam": copy a source mesh's triangle shapes onto a target (paper §3.2)
  Smooth,      ///< "smooth": feature-preserving smoothing, uniform weights (paper §4)
  Track,       ///< "track": one template through frames of any connectivity (paper §3.3)
};
inline constexpr EnumName<JobKind> kJobKindNames[] = {{"sequence", JobKind::Sequence},
                                                      {"remesh", JobKind::Remesh},
                                                      {"crossparam", JobKind::Crossparam},
                                                      {"smooth", JobKind::Smooth},
                                                      {"track", JobKind::Track}};

/// The JSON name of a job kind ("sequence", "remesh", "crossparam", "smooth", "track").
inline std::string job_name(JobKind job) {
  return std::string(name_of(job, kJobKindNames));
}

}  // namespace sm
