#pragma once
/// iterations.csv, the optimizer's course frame by frame (the paper's Figure 8): per iteration
/// the engine's figures (μ, energy, distances both ways, largest move, solver iterations) and,
/// where measured, the shear distortion (eq. 8) against the template.
///
/// The shear of the intermediate iterates is measured, for the frames asked, during the frame's
/// one run, by an observer of Massager::run (shear_observer) that sees every iterate.
#include <optional>
#include <string>
#include <vector>

#include "geometry/shear.hpp"
#include "io/csv.hpp"
#include "massage/massage.hpp"
#include "core/frame_selection.hpp"
#include "core/options_table.hpp"

namespace sm {

/// "output.iterations": iterations.csv, one row per logged frame and iteration (0 = the input).
struct IterationLogOptions {
  bool enabled = false;
  FrameSelection frames;  ///< frames logged
  /// Frames whose shear is measured after every iteration of their one run (logged even when not
  /// among `frames`); the other logged frames get shear at iteration 0 and the last iteration.
  FrameSelection shear_frames = FrameSelection::none();
};

template <>
inline const Fields<IterationLogOptions>& fields_of<IterationLogOptions>() {
  using O = IterationLogOptions;
  static const Fields<O> fields = {
      field<&O::frames>("frames", any_value(), "optimized frames logged"),
      field<&O::shear_frames>("shear_frames", any_value(),
                              "frames whose shear is measured after every iteration (one "
                              "shear measure per iteration of the frame's run); the others get "
                              "shear at iteration 0 and at the last iteration only"),
  };
  return fields;
}

/// One row: iteration 0 is the input frame (no engine figures; distances 0, as the optimized
/// mesh starts on the reference surface), iteration k ≥ 1 the state after the k-th solve.
struct IterationRow {
  int iteration = 0;
  std::optional<IterationStats> stats;     ///< empty for iteration 0
  std::optional<DistortionSummary> shear;  ///< empty where not measured
};

/// The columns of iterations.csv: frame, file, iteration, the engine's figures that
/// iteration_fields() gives to iterations.csv (mu, energy, max_dist_m_to_n, rms_dist_m_to_n,
/// max_dist_n_to_m, rms_dist_n_to_m — m: the frame being optimized, n: the input frame's surface
/// and samples; closest-point distances, model units — max_move, solver_iterations,
/// solver_residual), then shear_max, shear_mean, shear_p95.
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

/// An observer for Massager::run that appends the shear summary (eq. 8 against `templ`, the
/// caller's labels) of every iterate to `out`, one entry per iteration.
IterationObserver shear_observer(const TriMesh& templ,
                                 std::vector<std::optional<DistortionSummary>>& out);

}  // namespace sm
