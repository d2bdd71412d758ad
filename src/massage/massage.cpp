#include "massage/massage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>

#include "massage/massage_keys.hpp"
#include "massage/massage_run.hpp"
#include "massage/massager_state.hpp"
#include "core/errors.hpp"

namespace sm {
namespace {

// OptionError names the member; the caller that knows the config path adds it (with_option_path).
void check_options(const MassageOptions& o, int n) {
  check_option_ranges(o);  // the ranges of fields_of<MassageOptions>()
  for (int v : o.pinned)
    if (v < 0 || v >= n)
      throw OptionError("pinned", "vertex " + std::to_string(v) +
                                      " is out of range (the mesh has " + std::to_string(n) +
                                      " vertices)");
  // The one check of weights given as numbers (C++, Python), in the config's words; a weights
  // file is checked as it is read, by line (io/vertex_weights.hpp).
  if (!o.vertex_weights.empty() && static_cast<int>(o.vertex_weights.size()) != n)
    throw OptionError("vertex_weights", "expected " + std::to_string(n) +
                                            " weights (one per template vertex), got " +
                                            std::to_string(o.vertex_weights.size()));
  const ValueSpec weight = closed(0, 1);  // NaN is outside it too
  for (size_t i = 0; i < o.vertex_weights.size(); ++i)
    if (!weight.contains(o.vertex_weights[i]))
      throw OptionError("vertex_weights[" + std::to_string(i) + "]",
                        number_reason(weight, o.vertex_weights[i]));
}

// A_w = W A + (I − W): row i of A scaled by w_i, 1 − w_i added to its diagonal. Rows with
// w_i = 1 are copied untouched (bit for bit), rows with w_i = 0 are pinned anyway.
void weight_shape_rows(MassagerState& s) {
  const int n = s.pattern.size();
  s.vertex_weight.assign(n, 1.0);
  for (int v = 0; v < n; ++v) s.vertex_weight[s.order.vertex_rank[v]] = s.options.vertex_weights[v];
  s.weighted = std::any_of(s.vertex_weight.begin(), s.vertex_weight.end(),
                           [](double w) { return w != 1.0; });
  if (!s.weighted) return;
  s.weighted_shape = s.pattern.shape_matrix();
  double* values = s.weighted_shape.valuePtr();
  const int* outer = s.weighted_shape.outerIndexPtr();
  for (int i = 0; i < n; ++i) {
    const double w = s.vertex_weight[i];
    if (w == 1.0) continue;
    if (w == 0.0) s.pinned[i] = 1;
    for (int p = outer[i]; p < outer[i + 1]; ++p) values[p] *= w;
    values[s.pattern.diagonal_slot(i)] += 1.0 - w;
  }
}

}  // namespace

Massager::Massager(const TriMesh& templ, MassageOptions options, const char* name)
    : impl_(std::make_unique<MassagerState>()) {
  validate_mesh(templ, name);
  if (templ.num_triangles() == 0) throw InputError(std::string(name) + ": the mesh has no triangles");
  const int n = templ.num_vertices();
  check_options(options, n);
  MassagerState& s = *impl_;
  s.options = std::move(options);
  s.F_in = templ.F;
  s.topology_in = std::make_shared<const Topology>(build_topology(templ));
  s.weights = compute_weights(templ, s.options.weights, s.options.boundary_weights);
  s.bvh_in = TriangleBvh(templ);
  // The internal labels: Λ's entries are moved, not recomputed, so the weights are the same.
  s.order = banded_order(templ);
  const TriMesh T{to_new_order(s.order, templ.V), to_new_order(s.order, templ.F)};
  s.F = T.F;
  s.templ = T.V;
  s.topology = std::make_shared<const Topology>(build_topology(T));
  {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<size_t>(s.weights.lambda.nonZeros()));
    for (int i = 0; i < n; ++i)
      for (SparseMatrixR::InnerIterator it(s.weights.lambda, i); it; ++it)
        entries.emplace_back(s.order.vertex_rank[i], s.order.vertex_rank[it.col()], it.value());
    s.lambda.resize(n, n);
    s.lambda.setFromTriplets(entries.begin(), entries.end());
    s.lambda.makeCompressed();
  }
  s.pattern = SystemPattern(shape_matrix(ShapeWeights{s.lambda, 0}), T.F);
  if (s.options.shape_target == ShapeTargetKind::Template)
    s.target = ShapeTarget(T, s.lambda, *s.topology);
  s.bvh = TriangleBvh(T);
  s.edges = unique_edges(T.F);
  s.pinned.assign(n, 0);
  for (int v : s.options.pinned) s.pinned[s.order.vertex_rank[v]] = 1;
  if (s.options.pin_boundary)
    for (int v = 0; v < n; ++v)
      if (s.topology->is_boundary_vertex[v]) s.pinned[v] = 1;
  // A vertex in no triangle has no shape to keep and no surface to stay on: it keeps its position
  // and takes no part in the distance energy (nor in Lawson's normalization).
  s.isolated.assign(n, 0);
  for (int v = 0; v < n; ++v)
    if (s.topology->vertex_triangles.size(v) == 0) {
      s.isolated[v] = s.pinned[v] = 1;
      ++s.num_isolated;
    }
  if (!s.options.vertex_weights.empty()) weight_shape_rows(s);
  for (unsigned char p : s.pinned) s.num_pinned += p;
}

Massager::~Massager() = default;
Massager::Massager(Massager&&) noexcept = default;
Massager& Massager::operator=(Massager&&) noexcept = default;

const MassageOptions& Massager::options() const { return impl_->options; }
const Topology& Massager::topology() const { return *impl_->topology_in; }
std::shared_ptr<const Topology> Massager::shared_topology() const { return impl_->topology_in; }
const ShapeWeights& Massager::weights() const { return impl_->weights; }
const Triangles& Massager::triangles() const { return impl_->F_in; }
int Massager::num_vertices() const { return impl_->pattern.size(); }
const TriangleBvh& Massager::template_bvh() const { return impl_->bvh_in; }

MassageResult Massager::run(const Positions& start, const Reference& reference,
                            const IterationObserver& observer) const {
  const int n = impl_->pattern.size();
  if (start.rows() != n) {
    std::ostringstream msg;
    msg << "the start positions have " << start.rows() << " vertices, the template " << n;
    throw InputError(msg.str());
  }
  if (!start.allFinite()) {
    MassageResult result;
    result.V = start;
    result.ok = false;
    result.failure = "the start positions contain NaN or infinite coordinates";
    return result;
  }
  MassageRun run(*impl_, start, reference);
  MassageRun::Step step;
  do {
    step = run.step();
    if (observer && step != MassageRun::Step::Failed) observer(run.last(), run.positions());
  } while (step == MassageRun::Step::Continue);
  return run.finish();
}

}  // namespace sm
