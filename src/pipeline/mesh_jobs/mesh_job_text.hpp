#pragma once
/// The console lines of a single-mesh job (report/run_text.hpp has the sequence job's).
#include <string>

#include "pipeline/mesh_jobs/mesh_job_types.hpp"

namespace sm {

/// "remesh a.off (1000 vertices), 15 iterations, 4 threads".
std::string mesh_job_start_text(const MeshJobPlan& plan);

/// "15 iterations in 1.20 s (whole run 2.00 s)".
std::string mesh_job_end_text(const MeshJobResult& result);

}  // namespace sm
