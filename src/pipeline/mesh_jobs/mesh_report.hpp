#pragma once
/// The tables and the report of the single-mesh jobs and of `seqmassage measure`: measures.csv
/// (one row per measured mesh), the text table printed on the terminal (laid out like the paper's
/// Tables 1–3), triangles.csv (one row per triangle) and report.json.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/measures.hpp"
#include "pipeline/mesh_jobs/mesh_job_types.hpp"

namespace sm {

/// One measured mesh: `stage` is "before" or "after" in a job, "measure" for the command.
struct MeasureRow {
  std::string stage;
  std::string mesh;       ///< name of the measured mesh M
  std::string reference;  ///< name of the reference N
  const MeshMeasures* measures = nullptr;
};

/// The columns of measures.csv: stage, mesh, reference, vertices, triangles, then for
/// D in {mesh_to_ref, ref_to_mesh}: dist_D_{max,mean,rms,max_rel,mean_rel,rms_rel,samples};
/// hausdorff, hausdorff_rel, diagonal, radius_ratio_min, radius_ratio_mean, shear_max,
/// shear_mean, shear_p95, shear_degenerate, one shear_hist_<lower edge> count per bin,
/// feature_edges, feature_dist_max, feature_dist_mean, feature_dist_max_rel,
/// feature_dist_mean_rel, dihedral_change_max, dihedral_change_mean, features_flattened.
/// Cells that do not apply (no template, other connectivity) are empty.
std::vector<std::string> measure_columns(const MeasureOptions& options);

/// measures.csv, one line per row.
std::string format_measures_csv(const std::vector<MeasureRow>& rows, const MeasureOptions& options);

/// The text table: the names of M, N (and T), distances per direction (rows as sub-rows, like the
/// paper's Tables 1 and 2), Hausdorff distance, radius ratio (like Table 3), shear against T (when
/// measured) and N's feature edges. `reference_quality` adds the radius ratio of N.
std::string format_measures_table(const std::vector<MeasureRow>& rows,
                                  const QualitySummary* reference_quality = nullptr,
                                  const std::string& template_name = "");

/// The table a single-mesh job prints: format_measures_table of the mesh before and, unless the
/// optimizer failed, after; with the reference's radius ratio for a remesh.
std::string format_mesh_job_table(const MeshJobPlan& plan, const MeshJobResult& result);

/// What a single-mesh job wrote, relative to output.dir: the mesh (unless the optimizer failed),
/// measures.csv, report.json and, with "per_triangle_csv", triangles.csv.
std::vector<std::string> mesh_job_output_names(const MeshJobPlan& plan,
                                               const MeshJobResult& result);

/// The measures of one mesh as JSON (non-finite numbers as "inf"/"nan" strings).
nlohmann::json measures_json(const MeshMeasures& measures);

/// triangles.csv: `triangle,radius_ratio_before,radius_ratio_after,shear_before,shear_after`
/// (shear columns empty without a template; "after" columns empty if the run failed).
std::string format_triangles_csv(const TriangleMeasures& before, const TriangleMeasures* after);

/// report.json of a single-mesh job: versions, the resolved config, inputs, what the optimizer
/// did (per iteration), the measures before and after, outputs, warnings and (with timings) the
/// run time.
nlohmann::json make_mesh_report(const MeshJobPlan& plan, const MeshJobResult& result);

}  // namespace sm
