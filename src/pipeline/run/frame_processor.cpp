#include "pipeline/run/frame_processor.hpp"

#include "geometry/ground_truth.hpp"
#include "io/csv.hpp"
#include "core/errors.hpp"
#include "mesh/mesh_check.hpp"
#include "pipeline/sequence/fold_check.hpp"
#include "pipeline/sequence/fold_repair.hpp"
#include "pipeline/sequence/iteration_log.hpp"

namespace sm {

namespace {

// "1 2 3": triangle k's corners, 1-based.
std::string corners(const Triangles& F, int k) {
  return std::to_string(F(k, 0) + 1) + " " + std::to_string(F(k, 1) + 1) + " " +
         std::to_string(F(k, 2) + 1);
}

}  // namespace

FrameProcessor::FrameProcessor(TriMesh templ, const SequenceJobOptions& config,
                               std::string template_source, int template_frame)
    : templ_(std::move(templ)),
      template_source_(std::move(template_source)),
      template_frame_(template_frame),
      optimize_template_(config.templ.optimize),
      samples_(config.massage.samples),
      checks_(config.checks),
      massage_(config.massage),
      massager_(with_option_path("massage",
                                 [&] {
                                   return std::make_shared<const Massager>(
                                       templ_, config.massage, template_source_.c_str());
                                 })),
      meter_(templ_.F, templ_.num_vertices(), massager_->shared_topology(), config.measures) {}

std::string FrameProcessor::connectivity_mismatch(const std::string& who,
                                                  const TriMesh& frame) const {
  const TriMesh& t = templ_;
  const std::string like = ", but the template, " + template_source_ + ", has ";
  if (frame.num_vertices() != t.num_vertices())
    return who + ": " + std::to_string(frame.num_vertices()) + " vertices" + like +
           std::to_string(t.num_vertices());
  if (frame.num_triangles() != t.num_triangles())
    return who + ": " + std::to_string(frame.num_triangles()) + " triangles" + like +
           std::to_string(t.num_triangles());
  for (int k = 0; k < t.num_triangles(); ++k) {
    if (frame.F.row(k) == t.F.row(k)) continue;
    return who + ": faces differ from the template's, " + template_source_ + ": triangle " +
           std::to_string(k + 1) + " has vertices " + corners(frame.F, k) + ", the template's " +
           corners(t.F, k) + " (1-based)";
  }
  return "";
}

ProcessedFrame FrameProcessor::start(int index, SourceFrame input, const std::string& label) const {
  if (std::string problem = connectivity_mismatch(label, input.mesh); !problem.empty())
    throw InputError(problem);
  ProcessedFrame f;
  f.index = index;
  f.input = std::move(input);
  FrameSummary& s = f.summary;
  s.frame = index;
  s.warnings = f.input.warnings;
  s.vertices = f.input.mesh.num_vertices();
  s.triangles = f.input.mesh.num_triangles();
  f.shear_before = shear_distortion(templ_.V, f.input.mesh.V, templ_.F);
  f.V = f.input.mesh.V;
  return f;
}

void FrameProcessor::optimize(ProcessedFrame& f, const std::string& label,
                              bool shear_per_iteration) const {
  FrameSummary& s = f.summary;
  if (f.index == template_frame_ && !optimize_template_) {
    s.status = FrameStatus::Template;
    return;
  }
  if (std::string bad = non_finite_positions(f.input.mesh.V); !bad.empty()) {
    s.status = FrameStatus::Failed;  // only a source that does not check its frames gets here
    s.failure = "non-finite positions: input " + bad;
    return;
  }
  f.reference.emplace(f.input.mesh, samples_, label.c_str(), massager_->shared_topology(),
                      &massager_->template_bvh());
  f.result = shear_per_iteration ? massager_->run(f.input.mesh.V, *f.reference,
                                                  shear_observer(templ_, f.shear_per_iteration))
                                 : massager_->run(f.input.mesh.V, *f.reference);
  s.iterations = static_cast<int>(f.result.iterations.size());
  if (f.result.ok && checks_.repair_folds) repair(f);
}

// The fold limit (checks.max_folded_*) that `folded` triangles exceed, or "".
std::string FrameProcessor::fold_limit_exceeded(int folded) const {
  const int m = static_cast<int>(templ_.F.rows());
  if (checks_.max_folded_triangles && folded > *checks_.max_folded_triangles)
    return "checks.max_folded_triangles = " + std::to_string(*checks_.max_folded_triangles);
  if (checks_.max_folded_fraction && folded > *checks_.max_folded_fraction * m)
    return "checks.max_folded_fraction = " + format_number(*checks_.max_folded_fraction) + " of " +
           std::to_string(m) + " triangles";
  return "";
}

// checks.repair_folds: when the optimized positions have more folded triangles than the limits
// allow (with max_folded_triangles 0: any), solves again with the folded region pulled back
// towards the input until no fold is left (fold_repair.hpp); a repaired frame takes the new
// positions and says so in its warnings, a frame that cannot be repaired keeps its first result,
// which check() then fails as before. Frames within the limits are left as they are.
void FrameProcessor::repair(ProcessedFrame& f) const {
  MassageResult& result = f.result;
  FrameSummary& s = f.summary;
  if (!non_finite_positions(result.V).empty()) return;
  const Topology& topology = massager_->topology();
  std::vector<int> folded;
  const int count =
      count_folded_triangles(templ_.F, topology, f.input.mesh.V, result.V, &folded).folded;
  f.folded = count;
  if (count == 0 || fold_limit_exceeded(count).empty()) return;
  const FoldRepair fix = repair_folds(templ_, massage_, topology, f.input.mesh.V, *f.reference,
                                      folded, checks_.repair_rings, checks_.repair_rounds);
  const std::string what = "fold repair: " + std::to_string(count) + " folded triangles";
  const std::string rounds = std::to_string(fix.rounds) + (fix.rounds == 1 ? " round" : " rounds");
  if (fix.repaired) {
    result.V = fix.V;
    f.folded = 0;
    s.warnings.push_back(what + " repaired in " + rounds + ", " +
                         std::to_string(fix.pinned) + " vertices kept at the input and " +
                         std::to_string(fix.weighted) + " pulled towards it");
  } else {
    s.warnings.push_back(what + " not repaired: " +
                         (fix.failure.empty() ? std::to_string(fix.folded_left) +
                                                    " still folded after " + rounds
                                              : "the re-solve failed: " + fix.failure));
  }
}

std::string FrameProcessor::fold_check(const ProcessedFrame& f, const Positions& V,
                                       int& folded) const {
  folded = f.folded ? *f.folded
                    : count_folded_triangles(templ_.F, massager_->topology(), f.input.mesh.V, V)
                          .folded;
  const std::string over = fold_limit_exceeded(folded);
  if (over.empty()) return "";
  return "folded triangles: " + std::to_string(folded) +
         " output triangles are folded over (normal opposed to the input frame's), more than " +
         over;
}

void FrameProcessor::check(ProcessedFrame& f) const {
  if (!f.reference) return;  // not optimized: template or failed already
  FrameSummary& s = f.summary;
  if (!f.result.ok) {
    s.status = FrameStatus::Failed;
    s.failure = "optimizer failed: " + f.result.failure;
    return;
  }
  if (std::string bad = non_finite_positions(f.result.V); !bad.empty()) {
    s.status = FrameStatus::Failed;
    s.failure = "non-finite positions: output " + bad;
    return;
  }
  if (std::string bad = fold_check(f, f.result.V, s.folded_triangles); !bad.empty()) {
    s.status = FrameStatus::Failed;
    s.failure = std::move(bad);
    return;
  }
  s.status = FrameStatus::Optimized;
  f.V = f.result.V;
  f.unchanged = false;
}

void FrameProcessor::measure(ProcessedFrame& f) const {
  FrameSummary& s = f.summary;
  if (!f.unchanged) {
    const FrameDistances d = with_option_path("measures", [&] {
      return meter_.measure(f.input.mesh, f.reference->bvh(), f.reference->planes(), f.V);
    });
    s.out_to_in = d.moved_to_original;
    s.in_to_out = d.original_to_moved;
  }
  f.shear_after = f.unchanged ? f.shear_before : shear_distortion(templ_.V, f.V, templ_.F);
  s.shear_before = summarize_distortion(f.shear_before);
  s.shear_after = summarize_distortion(f.shear_after);
  if (const std::optional<Positions>& clean = f.input.ground_truth) {
    const double unit = mean_edge_length(templ_);
    const Eigen::VectorXd e_in = (f.input.mesh.V - *clean).rowwise().norm() / unit;
    const Eigen::VectorXd e_out = (f.V - *clean).rowwise().norm() / unit;
    const TriMesh truth{*clean, templ_.F};
    s.ground_truth = GroundTruthError{e_in.mean(), e_in.maxCoeff(), e_out.mean(), e_out.maxCoeff(),
                                      correspondence_error(f.input.mesh.V, truth, unit),
                                      correspondence_error(f.V, truth, unit)};
  }
}

std::vector<OutputFrame> FrameProcessor::encode(
    const ProcessedFrame& f, const std::vector<std::shared_ptr<FrameOutput>>& outputs) const {
  const FrameOutcome outcome{f.index,         &f.input,        &f.V,
                             f.unchanged,     &f.shear_before, &f.shear_after,
                             f.reference ? &f.result : nullptr, &f.shear_per_iteration};
  std::vector<OutputFrame> parts;
  parts.reserve(outputs.size());
  for (const auto& output : outputs) parts.push_back(output->encode(outcome));
  return parts;
}

}  // namespace sm
