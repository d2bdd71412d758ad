#pragma once
/// The single-mesh jobs, with the paper's roles (M the mesh optimized, T the shape template, N the
/// reference surface):
///
///   "remesh"      §3.3  M = a remesh, T = M itself, N = its source surface (any connectivity)
///   "crossparam"  §3.2  M = a target mesh, T = a source mesh with M's connectivity, N = M as
///   loaded "smooth"      §4    M = the mesh, uniform (or mean value) weights of M, N = M as loaded
///
/// A job is planned (every input read and checked, nothing written), then run: one Massager run,
/// the paper's measures before and after, and the outputs <output.dir>/<input file name>,
/// measures.csv, report.json (and triangles.csv on request), each written atomically.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/mesh_jobs/mesh_job_options.hpp"
#include "pipeline/mesh_jobs/mesh_job_types.hpp"

namespace sm {

/// Reads the mesh (and the reference or template), checks them (connectivity of the template,
/// mesh validity, options such as pinned indices) and builds the Massager; refuses an output that
/// would overwrite an input. Throws ConfigError, InputError (naming the file) or IoError.
MeshJobPlan plan_mesh_job(const MeshJobOptions& config);

/// What a run of `plan` would do, several lines of text (for --dry-run).
std::string describe_mesh_plan(const MeshJobPlan& plan);

/// Runs the job and writes its outputs, holding the output folder's lock (lock_output_folder:
/// IoError if another run holds it). A numerical failure of the optimizer is recorded in the
/// result (no mesh is written then; measures.csv holds the "before" row and report.json the
/// reason), not thrown. Same plan, same output bytes (apart from timings) for any thread count.
MeshJobResult run_mesh_job(const MeshJobPlan& plan);

/// The output mesh's path for `config`: <output.dir>/<input file name>, with the extension of
/// output.format unless it is "same".
std::filesystem::path mesh_output_path(const MeshJobOptions& config);

}  // namespace sm
