#pragma once
/// report.html of a single-mesh job (remesh, crossparam, smooth): the mesh as loaded and the
/// output side by side in the report's 3D player (one frame), coloured by the shear against T
/// (eq. 8; crossparam and smooth) or by the radius ratio (remesh), with measures.csv as the table,
/// the histogram of the colours' measure, warnings, config and versions (html_sequence.hpp).
#include <string>

#include <nlohmann/json.hpp>

#include "pipeline/mesh_jobs/mesh_job_types.hpp"

namespace sm {

/// The page; `measures_csv` is measures.csv's text, `report` the job's report.json (config,
/// versions). The budget is plan.config.output.html_max_mb.
std::string mesh_html_page(const MeshJobPlan& plan, const MeshJobResult& result,
                           const std::string& measures_csv, const nlohmann::json& report);

}  // namespace sm
