#include "massage/massage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>

#include "massage/correspondence.hpp"
#include "massage/linear_solver.hpp"
#include "massage/system.hpp"
#include "mesh/errors.hpp"
#include "mesh/reorder.hpp"
#include "mesh/timing.hpp"

namespace sm {
namespace {

void check_options(const MassageOptions& o, int n) {
  auto bad = [](const std::string& key, const std::string& why) {
    throw ConfigError("massage." + key + ": " + why);
  };
  if (o.iterations < 1) bad("iterations", "must be >= 1");
  if (o.mu && !(*o.mu >= 0.0 && *o.mu < 1.0)) bad("mu", "must be \"auto\" or in [0, 1)");
  if (!(o.tolerance >= 0.0)) bad("tolerance", "must be >= 0");
  if (!(o.lawson_floor > 0.0 && o.lawson_floor < 1.0)) bad("lawson_floor", "must be in (0, 1)");
  if (!(o.solver_tolerance > 0.0 && o.solver_tolerance < 1.0))
    bad("solver_tolerance", "must be in (0, 1)");
  if (o.solver_max_iterations < 1) bad("solver_max_iterations", "must be >= 1");
  if (o.walk_max_steps < 0) bad("walk_max_steps", "must be >= 0");
  for (int v : o.pinned)
    if (v < 0 || v >= n)
      bad("pinned", "vertex " + std::to_string(v) + " is out of range (the mesh has " +
                        std::to_string(n) + " vertices)");
}

// Lawson's update (eq. 5) for α and β together, then normalisation by the joint mean and a floor
// relative to it, so the weights neither underflow nor overflow and B stays definite. Vertices of
// M in no triangle (`isolated`, `num_isolated` of them) take no part: their α stays 0.
void lawson_update(Eigen::VectorXd& alpha, const Eigen::VectorXd& d_alpha, Eigen::VectorXd& beta,
                   const Eigen::VectorXd& d_beta, double floor,
                   const std::vector<unsigned char>& isolated, int num_isolated) {
  alpha = alpha.cwiseProduct(d_alpha);
  beta = beta.cwiseProduct(d_beta);
  const double total = alpha.sum() + beta.sum();
  const double count = static_cast<double>(alpha.size() - num_isolated + beta.size());
  if (!(total > 0.0) || !std::isfinite(total)) {
    alpha.setOnes();
    beta.setOnes();
  } else {
    const double mean = total / count;
    alpha = (alpha / mean).cwiseMax(floor);
    beta = (beta / mean).cwiseMax(floor);
  }
  if (num_isolated > 0)
    for (Eigen::Index i = 0; i < alpha.size(); ++i)
      if (isolated[i]) alpha[i] = 0.0;
}

}  // namespace

// run() works on the template's vertices and triangles relabelled in a banded order
// (mesh/reorder.hpp), for the caches and ILU(0); the interface (accessors, run's start and result) keeps the
// caller's labels. `F`, `topology`, `bvh`, `lambda`, `pattern`, `target`, the flags and edges are
// in the internal order; `*_in` are the caller's.
struct Massager::Impl {
  MassageOptions options;
  MeshOrder order;
  Triangles F, F_in;
  std::shared_ptr<const Topology> topology, topology_in;
  ShapeWeights weights;  // the caller's labels (weights())
  SparseMatrixR lambda;  // Λ relabelled
  SystemPattern pattern;
  ShapeTarget target;                     // with ShapeTargetKind::Template
  TriangleBvh bvh;                        // over the template; copied and refitted per run
  TriangleBvh bvh_in;                     // the same in the caller's labels (template_bvh())
  std::vector<std::array<int, 2>> edges;  // for the mean edge length of M
  std::vector<unsigned char> pinned;      // n flags
  int num_pinned = 0;
  std::vector<unsigned char> isolated;    // n flags: vertices in no triangle (also pinned)
  int num_isolated = 0;
};

namespace {

// The starting correspondences when M and N share the connectivity: vertex i of M starts on the
// first triangle around vertex i (none for a vertex in no triangle); with `samples`, for N's
// samples, whose first ones are N's vertices that lie in a triangle, in order.
std::vector<SurfacePoint> vertex_hints(const Topology& topo, int count, bool samples) {
  std::vector<SurfacePoint> hints(count);
  for (int v = 0, j = 0; v < topo.num_vertices && j < count; ++v) {
    if (topo.vertex_triangles.size(v) > 0)
      hints[j].triangle = topo.vertex_triangles.data[topo.vertex_triangles.begin(v)];
    if (!samples || topo.vertex_triangles.size(v) > 0) ++j;
  }
  return hints;
}

}  // namespace

Massager::Massager(const TriMesh& templ, MassageOptions options, const char* name)
    : impl_(std::make_unique<Impl>()) {
  validate_mesh(templ, name);
  if (templ.num_triangles() == 0) throw InputError(std::string(name) + ": the mesh has no triangles");
  const int n = templ.num_vertices();
  check_options(options, n);
  Impl& s = *impl_;
  s.options = std::move(options);
  s.F_in = templ.F;
  s.topology_in = std::make_shared<const Topology>(build_topology(templ));
  s.weights = compute_weights(templ, s.options.weights, s.options.boundary_weights);
  s.bvh_in = TriangleBvh(templ);
  // The internal labels: Λ's entries are moved, not recomputed, so the weights are the same.
  s.order = banded_order(templ);
  const TriMesh T{to_new_order(s.order, templ.V), to_new_order(s.order, templ.F)};
  s.F = T.F;
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

MassageResult Massager::run(const Positions& start_in, const Reference& reference_in) const {
  const Impl& s = *impl_;
  const MassageOptions& o = s.options;
  const auto t_run = Clock::now();
  const int n = s.pattern.size();
  MassageResult result;
  result.V = start_in;
  if (start_in.rows() != n) {
    std::ostringstream msg;
    msg << "the start positions have " << start_in.rows() << " vertices, the template " << n;
    throw InputError(msg.str());
  }
  if (!start_in.allFinite()) {
    result.ok = false;
    result.failure = "the start positions contain NaN or infinite coordinates";
    return result;
  }
  // Into the internal labels: the start, and N when it has the template's connectivity (then
  // relabelled the same way, with the internal topology and a refit of the internal BVH).
  const Positions start = to_new_order(s.order, start_in);
  std::optional<Reference> relabelled;
  if (reference_in.mesh().F.rows() == s.F_in.rows() && reference_in.mesh().F == s.F_in)
    relabelled.emplace(TriMesh{to_new_order(s.order, reference_in.mesh().V), s.F},
                       reference_in.sample_kind(), "reference", s.topology, &s.bvh);
  const Reference& reference = relabelled ? *relabelled : reference_in;

  // Per-run state: M's positions, BVH (the template's tree, refitted only when an exact query on
  // M needs it) and projection frames; correspondences both ways; Lawson weights.
  TriMesh M{start, s.F};
  TriangleBvh bvh_m;  // copied from the template's on first use
  bool bvh_m_current = false;
  auto refit_m = [&] {
    if (bvh_m.empty()) bvh_m = s.bvh;
    if (!bvh_m_current) bvh_m.refit(M.V);
    bvh_m_current = true;
  };
  // (Without bends: recomputing them every iteration costs more than they save on M.)
  TrianglePlanes planes_m(M.V, s.F);
  const TriMesh& N = reference.mesh();
  const Positions& W = reference.samples();
  const SurfaceView on_n{&N.V, &N.F, &reference.topology(), &reference.bvh(), &reference.planes()};
  const SurfaceView on_m{&M.V, &M.F, s.topology.get(), &bvh_m, &planes_m};
  // With the same connectivity, vertex i of M and the sample of N's vertex i start at each
  // other's vertex i: a bound that makes the first, exact queries cheap (free when M starts on N).
  std::vector<SurfacePoint> v_hat, w_hat;  // v̂_i on N, ŵ_j on M
  if (N.F.rows() == s.F.rows() && N.F == s.F) {
    v_hat = vertex_hints(*s.topology, n, false);
    w_hat = vertex_hints(*s.topology, static_cast<int>(W.rows()), true);
  }
  const bool exact = o.closest_points == ClosestPointMode::Exact;
  update_correspondences(on_n, M.V, true, o.walk_max_steps, v_hat);
  update_correspondences(on_m, W, true, o.walk_max_steps, w_hat, refit_m);
  Eigen::VectorXd alpha = Eigen::VectorXd::Ones(n), beta = Eigen::VectorXd::Ones(W.rows());
  for (int i = 0; i < n; ++i)
    if (s.isolated[i]) alpha[i] = 0.0;  // no part in the distance energy (and pinned)
  Eigen::VectorXd d_alpha(n), d_beta(W.rows());

  const double move_limit = o.tolerance * mean_edge_length(M.V, s.edges);
  SparseMatrixR K = s.pattern.shape_matrix();  // values overwritten every iteration
  const std::vector<double> A_values(K.valuePtr(), K.valuePtr() + K.nonZeros());
  std::vector<double> B_values;
  Positions c, rhs, X, AV, V_prev, delta;
  const bool use_target = o.shape_target == ShapeTargetKind::Template;
  if (use_target)  // once per run, from the start (see shape_target.hpp)
    result.target_fallback_vertices =
        s.target.evaluate(start, s.F, s.lambda, *s.topology, delta);
  Ilu0 ilu;
  BicgstabWorkspace workspace;
  DirectSolver direct;

  for (int k = 1; k <= o.iterations; ++k) {
    IterationStats it;
    it.iteration = k;
    auto t0 = Clock::now();
    assemble_distance_system(s.pattern, s.F, v_hat, alpha, W, w_hat, beta, B_values, c);
    double b_norm2 = 0.0;
    for (double b : B_values) b_norm2 += b * b;
    const double mu =
        o.mu ? *o.mu : std::sqrt(b_norm2) / (3.0 * s.pattern.shape_norm() + std::sqrt(b_norm2));
    it.mu = mu;
    double* kv = K.valuePtr();
    for (size_t p = 0; p < B_values.size(); ++p)
      kv[p] = mu * A_values[p] + (1.0 - mu) * B_values[p];
    rhs = (1.0 - mu) * c;
    if (use_target) rhs += mu * delta;
    if (s.num_pinned > 0) {
      const int* outer = K.outerIndexPtr();
      for (int i = 0; i < n; ++i) {
        if (!s.pinned[i]) continue;
        for (int p = outer[i]; p < outer[i + 1]; ++p) kv[p] = 0.0;
        kv[s.pattern.diagonal_slot(i)] = 1.0;
        rhs.row(i) = start.row(i);
      }
    }
    SolveStats solve;
    bool use_direct = o.solver == SolverKind::Direct;
    if (!use_direct && !ilu.factor(K, s.pattern.ilu_schedule())) use_direct = true;
    it.seconds_assemble = seconds_since(t0);

    t0 = Clock::now();
    // Warm start: the positions extrapolated along the last step, 2 v_k − v_{k−1} (the iterates
    // move smoothly; 2.0 -> 1.2 BiCGSTAB iterations at 10k, 3.0 -> 2.7 on the crane), the current
    // positions in the first iteration.
    if (k > 1) {
      X.resize(n, 3);
      for (Eigen::Index p = 0; p < X.size(); ++p)
        X.data()[p] = 2.0 * M.V.data()[p] - V_prev.data()[p];
    } else {
      X = M.V;
    }
    if (!use_direct) {
      const std::array<double, 3> scale = centred_scale(K, rhs, M.V, s.pinned);
      solve = bicgstab(K, ilu, rhs, X, o.solver_tolerance, o.solver_max_iterations, workspace,
                       &scale);
      if (!solve.ok) {
        X = M.V;
        use_direct = true;  // the robust path for this iteration
      }
    }
    if (use_direct) {
      const int iterative_steps = solve.iterations;
      solve = direct.solve(K, rhs, X);
      solve.iterations += iterative_steps;
    }
    it.seconds_solve = seconds_since(t0);
    it.solver_iterations = solve.iterations;
    it.solver_residual = solve.residual;
    if (!solve.ok || !X.allFinite()) {
      result.ok = false;
      result.failure = "iteration " + std::to_string(k) + ": " +
                       (solve.ok ? std::string("the solution contains NaN") : solve.message);
      result.V = start_in;
      result.iterations.push_back(it);
      result.seconds = seconds_since(t_run);
      return result;
    }
    it.max_move = (X - M.V).rowwise().norm().maxCoeff();
    V_prev.swap(M.V);
    M.V = X;

    t0 = Clock::now();
    bvh_m_current = false;
    it.exact_queries = update_correspondences(on_n, M.V, exact, o.walk_max_steps, v_hat);
    // M's frames just before the walks that read them, while they are still in the cache.
    planes_m.update(M.V, s.F);
    it.exact_queries += update_correspondences(on_m, W, exact, o.walk_max_steps, w_hat, refit_m);
    it.seconds_closest = seconds_since(t0);

    for (int i = 0; i < n; ++i) d_alpha[i] = s.isolated[i] ? 0.0 : std::sqrt(v_hat[i].dist2);
    for (int j = 0; j < d_beta.size(); ++j) d_beta[j] = std::sqrt(w_hat[j].dist2);
    multiply(s.pattern.shape_matrix(), M.V, AV);
    if (use_target) AV -= delta;
    it.energy = mu * AV.squaredNorm() +
                (1.0 - mu) * (alpha.dot(d_alpha.cwiseAbs2()) + beta.dot(d_beta.cwiseAbs2()));
    it.max_dist_m_to_n = d_alpha.maxCoeff();
    it.rms_dist_m_to_n = std::sqrt(d_alpha.squaredNorm() / n);
    it.max_dist_n_to_m = d_beta.size() ? d_beta.maxCoeff() : 0.0;
    it.rms_dist_n_to_m = d_beta.size() ? std::sqrt(d_beta.squaredNorm() / d_beta.size()) : 0.0;
    result.iterations.push_back(it);

    if (o.lawson)
      lawson_update(alpha, d_alpha, beta, d_beta, o.lawson_floor, s.isolated, s.num_isolated);
    if (k < o.iterations && it.max_move <= move_limit) {
      result.stopped_early = true;
      break;
    }
  }

  // Fold-over check: a triangle of M whose normal opposes the normal of N where its corners land.
  const Positions nm = triangle_normals(M);
  const Positions nn = triangle_normals(N);
  for (int t = 0; t < M.num_triangles(); ++t) {
    Vec3 ref = Vec3::Zero();
    for (int a = 0; a < 3; ++a) ref += nn.row(v_hat[M.F(t, a)].triangle).transpose();
    if (nm.row(t).dot(ref) < 0.0) ++result.folded_triangles;
  }
  result.V = to_old_order(s.order, M.V);
  result.seconds = seconds_since(t_run);
  return result;
}

}  // namespace sm
