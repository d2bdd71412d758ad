#pragma once
/// iterations.csv, the optimizer's course frame by frame (the paper's Figure 8): per iteration
/// the engine's figures (μ, energy, distances both ways, largest move, solver iterations) and,
/// where measured, the shear distortion (eq. 8) against the template.
///
/// The engine reports distances after every iteration but not positions, so the shear of an
/// intermediate iterate is measured, for the frames asked, by running the optimizer again with
/// 1, 2, ..., K − 1 iterations from the same start and reference: its first j iterations are the
/// full run's, so the result is the j-th iterate exactly. Each re-run is checked against the full
/// run's iteration j (μ, energy, distances and move, bit for bit); where they differ the shear is
/// left empty and a warning says so.
#include <optional>
#include <string>
#include <vector>

#include "geometry/shear.hpp"
#include "io/csv.hpp"
#include "massage/massage.hpp"

namespace sm {

/// One row: iteration 0 is the input frame (no engine figures; distances 0, as the optimized
/// mesh starts on the reference surface), iteration k ≥ 1 the state after the k-th solve.
struct IterationRow {
  int iteration = 0;
  std::optional<IterationStats> stats;     ///< empty for iteration 0
  std::optional<DistortionSummary> shear;  ///< empty where not measured
};

/// The columns of iterations.csv: frame, file, iteration, mu, energy, max_dist_m_to_n,
/// rms_dist_m_to_n, max_dist_n_to_m, rms_dist_n_to_m (m: the frame being optimized, n: the input
/// frame's surface and samples; the engine's closest-point distances, model units), max_move,
/// solver_iterations, solver_residual, shear_max, shear_mean, shear_p95.
std::vector<std::string> iteration_columns();

/// The rows of one optimized frame: iteration 0 with `before`, every iteration of `result` with
/// `shear_per_iteration[k - 1]` where given (else empty), the last with `after` when the run
/// succeeded.
std::vector<IterationRow> iteration_rows(
    const MassageResult& result, const DistortionSummary& before, const DistortionSummary& after,
    const std::vector<std::optional<DistortionSummary>>& shear_per_iteration = {});

/// Appends `rows` of frame `frame` (file name `file`) to `csv` (made with iteration_columns()).
void append_iteration_rows(CsvWriter& csv, int frame, const std::string& file,
                           const std::vector<IterationRow>& rows);

/// The shear summary after each iteration j = 1 .. K − 1 of `full` (K = its iteration count; the
/// last iterate is full.V), by re-running an optimizer built on `templ` with `options` limited to
/// j iterations from `start` against `reference`. An entry is empty where the re-run failed or
/// differs from `full` at iteration j; `warning` then says which. Costs about K(K − 1)/2
/// iterations.
std::vector<std::optional<DistortionSummary>> shear_per_iteration(
    const TriMesh& templ, const MassageOptions& options, const Positions& start,
    const Reference& reference, const MassageResult& full, std::string& warning);

}  // namespace sm
