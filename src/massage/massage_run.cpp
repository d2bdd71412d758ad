#include "massage/massage_run.hpp"

#include <algorithm>
#include <cmath>

#include "massage/plane_term.hpp"
#include "core/timing.hpp"

namespace sm {
namespace {

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

// N in the internal labels when it has the template's connectivity (relabelled the same way, with
// the internal topology and a refit of the internal BVH), else N as given.
const Reference& internal_reference(const MassagerState& s, const Reference& reference,
                                    std::optional<Reference>& relabelled) {
  if (reference.mesh().F.rows() == s.F_in.rows() && reference.mesh().F == s.F_in)
    relabelled.emplace(TriMesh{to_new_order(s.order, reference.mesh().V), s.F},
                       reference.sample_kind(), "reference", s.topology, &s.bvh);
  return relabelled ? *relabelled : reference;
}

}  // namespace

MassageRun::MassageRun(const MassagerState& state, const Positions& start_in,
                       const Reference& reference_in)
    : s_(state),
      o_(state.options),
      t_run_(Clock::now()),
      start_in_(start_in),
      start_(to_new_order(state.order, start_in)),
      reference_(internal_reference(state, reference_in, relabelled_)),
      M_{start_, state.F},
      // (Without bends: recomputing them every iteration costs more than they save on M.)
      planes_m_(M_.V, state.F),
      on_n_{&reference_.mesh().V, &reference_.mesh().F, &reference_.topology(), &reference_.bvh(),
            &reference_.planes()},
      on_m_{&M_.V, &M_.F, state.topology.get(), &bvh_m_, &planes_m_} {
  const int n = s_.pattern.size();
  const TriMesh& N = reference_.mesh();
  const Positions& W = reference_.samples();
  result_.V = start_in;
  // With the same connectivity, vertex i of M and the sample of N's vertex i start at each
  // other's vertex i: a bound that makes the first, exact queries cheap (free when M starts on N).
  if (N.F.rows() == s_.F.rows() && N.F == s_.F) {
    v_hat_ = vertex_hints(*s_.topology, n, false);
    w_hat_ = vertex_hints(*s_.topology, static_cast<int>(W.rows()), true);
  }
  update_correspondences(on_n_, M_.V, true, o_.walk_max_steps, v_hat_);
  update_correspondences(on_m_, W, true, o_.walk_max_steps, w_hat_, [this] { refit_m(); });
  alpha_ = Eigen::VectorXd::Ones(n);
  beta_ = Eigen::VectorXd::Ones(W.rows());
  for (int i = 0; i < n; ++i)
    if (s_.isolated[i]) alpha_[i] = 0.0;  // no part in the distance energy (and pinned)
  d_alpha_.resize(n);
  d_beta_.resize(W.rows());
  move_limit_ = o_.tolerance * mean_edge_length(M_.V, s_.edges);
  K_ = s_.shape();
  A_values_.assign(K_.valuePtr(), K_.valuePtr() + K_.nonZeros());
  plane_ = o_.distance_term == DistanceTerm::Plane;
  if (plane_) {
    normals_n_ = vertex_normals(N);
    epsilon_ = tangential_stiffness(s_.templ, start_, s_.F, *s_.topology, o_.tangential_stiffness,
                                    o_.tangential_adapt, o_.tangential_smoothing);
    K_pre_ = K_;
  }
  use_target_ = o_.shape_target == ShapeTargetKind::Template;
  if (use_target_)  // once per run, from the start (see shape_target.hpp)
    result_.target_fallback_vertices =
        s_.target.evaluate(start_, s_.F, s_.lambda, *s_.topology, delta_);
  if (s_.weighted) {  // δ_w = W δ + (I − W) p, p the start (docs/method-vertex-weights.md)
    if (!use_target_) delta_.setZero(n, 3);
    use_target_ = true;
    for (int i = 0; i < n; ++i)
      if (const double w = s_.vertex_weight[i]; w != 1.0)
        delta_.row(i) = w * delta_.row(i) + (1.0 - w) * start_.row(i);
  }
}

MassageRun::Step MassageRun::step() {
  const int k = ++k_;
  IterationStats it;
  it.iteration = k;
  const bool use_direct = assemble(it);
  if (!solve(it, use_direct, k)) return Step::Failed;
  closest_points(it);
  measure(it);
  result_.iterations.push_back(it);
  if (o_.lawson)
    lawson_update(alpha_, d_alpha_, beta_, d_beta_, o_.lawson_floor, s_.isolated, s_.num_isolated);
  if (k >= o_.iterations) return Step::Done;
  if (it.max_move <= move_limit_) {
    result_.stopped_early = true;
    return Step::Done;
  }
  return Step::Continue;
}

// B and c (eq. 4) on the fixed pattern, μ, K's values and the right-hand side (eq. 7), the pinned
// rows, and the ILU(0) factors; true when the direct solver is to be used.
bool MassageRun::assemble(IterationStats& it) {
  const auto t0 = Clock::now();
  const int n = s_.pattern.size();
  assemble_distance_system(s_.pattern, s_.F, {v_hat_, alpha_, reference_.samples(), w_hat_, beta_},
                           B_values_, c_);
  double b_norm2 = 0.0;
  for (double b : B_values_) b_norm2 += b * b;
  mu_ = o_.mu ? *o_.mu : std::sqrt(b_norm2) / (3.0 * s_.pattern.shape_norm() + std::sqrt(b_norm2));
  it.mu = mu_;
  double* kv = K_.valuePtr();
  for (size_t p = 0; p < B_values_.size(); ++p)
    kv[p] = mu_ * A_values_[p] + (1.0 - mu_) * B_values_[p];
  rhs_ = (1.0 - mu_) * c_;
  if (use_target_) rhs_ += mu_ * delta_;
  if (s_.num_pinned > 0) {
    const int* outer = K_.outerIndexPtr();
    for (int i = 0; i < n; ++i) {
      if (!s_.pinned[i]) continue;
      for (int p = outer[i]; p < outer[i + 1]; ++p) kv[p] = 0.0;
      kv[s_.pattern.diagonal_slot(i)] = 1.0;
      rhs_.row(i) = start_.row(i);
    }
  }
  if (plane_) add_plane_term();
  bool use_direct = o_.solver == SolverKind::Direct;
  const SparseMatrixR& preconditioned = plane_ ? K_pre_ : K_;
  if (!use_direct && !ilu_.factor(preconditioned, s_.pattern.ilu_schedule())) use_direct = true;
  it.seconds_assemble = seconds_since(t0);
  return use_direct;
}

// The plane term's blocks D for the current correspondences, their part of the right-hand side
// (−D v̂), and the preconditioner's matrix: K with D's mean diagonal taken off.
void MassageRun::add_plane_term() {
  const PlaneInputs in{s_.pattern, s_.F,
                       M_.V,       reference_.mesh().F,
                       normals_n_, reference_.samples(),
                       v_hat_,     w_hat_,
                       alpha_,     beta_,
                       epsilon_,   s_.pinned,
                       mu_};
  plane_blocks(in, D_, rhs_);
  double* kp = K_pre_.valuePtr();
  const double* k = K_.valuePtr();
  for (size_t p = 0; p < D_.size(); ++p) kp[p] = k[p] - (D_[p][0] + D_[p][1] + D_[p][2]) / 3.0;
}

// K v = rhs from a warm start; on success M takes the solution. False (and the run failed) when
// neither solver gives a finite solution.
bool MassageRun::solve(IterationStats& it, bool use_direct, int k) {
  const auto t0 = Clock::now();
  const int n = s_.pattern.size();
  // Warm start: the positions extrapolated along the last step, 2 v_k − v_{k−1} (the iterates
  // move smoothly, so the extrapolation is closer to the solution than v_k and BiCGSTAB needs
  // fewer iterations), the current positions in the first iteration.
  if (k > 1) {
    X_.resize(n, 3);
    for (Eigen::Index p = 0; p < X_.size(); ++p)
      X_.data()[p] = 2.0 * M_.V.data()[p] - V_prev_.data()[p];
  } else {
    X_ = M_.V;
  }
  SolveStats solve;
  if (!use_direct) {
    const std::array<double, 3> scale = centred_scale(K_, rhs_, M_.V, s_.pinned);
    solve = plane_ ? bicgstab_coupled(K_, D_, ilu_, rhs_, X_, o_.solver_tolerance,
                                      o_.solver_max_iterations, workspace_, scale)
                   : bicgstab(K_, ilu_, rhs_, X_, o_.solver_tolerance, o_.solver_max_iterations,
                              workspace_, &scale);
    if (!solve.ok) {
      X_ = M_.V;
      use_direct = true;  // the robust path for this iteration
    }
  }
  if (use_direct) {
    const int iterative_steps = solve.iterations;
    solve = plane_ ? solve_coupled_direct(K_, D_, rhs_, X_) : direct_.solve(K_, rhs_, X_);
    solve.iterations += iterative_steps;
  }
  it.seconds_solve = seconds_since(t0);
  it.solver_iterations = solve.iterations;
  it.solver_residual = solve.residual;
  if (!solve.ok || !X_.allFinite()) {
    fail(it, "iteration " + std::to_string(k) + ": " +
                 (solve.ok ? std::string("the solution contains NaN") : solve.message));
    return false;
  }
  it.max_move = (X_ - M_.V).rowwise().norm().maxCoeff();
  V_prev_.swap(M_.V);
  M_.V = X_;
  return true;
}

// M's BVH (the template's tree, copied on first use), refitted only when an exact query on M
// needs it.
void MassageRun::refit_m() {
  if (bvh_m_.empty()) bvh_m_ = s_.bvh;
  if (!bvh_m_current_) bvh_m_.refit(M_.V);
  bvh_m_current_ = true;
}

void MassageRun::fail(IterationStats& it, const std::string& why) {
  result_.ok = false;
  result_.failure = why;
  result_.V = start_in_;
  result_.iterations.push_back(it);
}

// The correspondences both ways for the new positions (§2.2.1).
void MassageRun::closest_points(IterationStats& it) {
  const auto t0 = Clock::now();
  const bool exact = o_.closest_points == ClosestPointMode::Exact;
  bvh_m_current_ = false;
  it.exact_queries = update_correspondences(on_n_, M_.V, exact, o_.walk_max_steps, v_hat_);
  // M's frames just before the walks that read them, while they are still in the cache.
  planes_m_.update(M_.V, s_.F);
  it.exact_queries += update_correspondences(on_m_, reference_.samples(), exact, o_.walk_max_steps,
                                             w_hat_, [this] { refit_m(); });
  it.seconds_closest = seconds_since(t0);
}

// The distances both ways (they are also Lawson's factors) and the energy after the solve.
void MassageRun::measure(IterationStats& it) {
  const int n = s_.pattern.size();
  for (int i = 0; i < n; ++i) d_alpha_[i] = s_.isolated[i] ? 0.0 : std::sqrt(v_hat_[i].dist2);
  for (int j = 0; j < d_beta_.size(); ++j) d_beta_[j] = std::sqrt(w_hat_[j].dist2);
  multiply(s_.shape(), M_.V, AV_);
  if (use_target_) AV_ -= delta_;
  it.energy = mu_ * AV_.squaredNorm() +
              (1.0 - mu_) * (alpha_.dot(d_alpha_.cwiseAbs2()) + beta_.dot(d_beta_.cwiseAbs2()));
  it.max_dist_m_to_n = d_alpha_.maxCoeff();
  it.rms_dist_m_to_n = std::sqrt(d_alpha_.squaredNorm() / n);
  it.max_dist_n_to_m = d_beta_.size() ? d_beta_.maxCoeff() : 0.0;
  it.rms_dist_n_to_m = d_beta_.size() ? std::sqrt(d_beta_.squaredNorm() / d_beta_.size()) : 0.0;
}

Positions MassageRun::positions() const {
  return to_old_order(s_.order, M_.V);
}

MassageResult MassageRun::finish() {
  if (result_.ok) {
    // Fold-over check: a triangle of M whose normal opposes the normal of N where its corners
    // land.
    const Positions nm = triangle_normals(M_);
    const Positions nn = triangle_normals(reference_.mesh());
    for (int t = 0; t < M_.num_triangles(); ++t) {
      Vec3 ref = Vec3::Zero();
      for (int a = 0; a < 3; ++a) ref += nn.row(v_hat_[M_.F(t, a)].triangle).transpose();
      if (nm.row(t).dot(ref) < 0.0) ++result_.folded_triangles;
    }
    result_.V = to_old_order(s_.order, M_.V);
  }
  result_.seconds = seconds_since(t_run_);
  return std::move(result_);
}

}  // namespace sm
