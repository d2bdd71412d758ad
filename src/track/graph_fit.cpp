#include "track/graph_fit.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "core/errors.hpp"
#include "track/block_cholesky.hpp"

namespace sm {

namespace {

using Block = Eigen::Matrix<double, 6, 6>;

// Every `count`-th of `n` items spread evenly: at most `max` indices out of `candidates`.
std::vector<int> spread(const std::vector<int>& candidates, int max) {
  const size_t n = candidates.size();
  if (n <= static_cast<size_t>(max)) return candidates;
  std::vector<int> out;
  out.reserve(max);
  for (int k = 0; k < max; ++k) out.push_back(candidates[(n * static_cast<size_t>(k)) / max]);
  return out;
}

std::vector<int> used_vertices(const TriMesh& mesh) {
  std::vector<uint8_t> used(mesh.num_vertices(), 0);
  for (int t = 0; t < mesh.num_triangles(); ++t)
    for (int c = 0; c < 3; ++c) used[mesh.F(t, c)] = 1;
  std::vector<int> out;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (used[v]) out.push_back(v);
  return out;
}

double robust_weight(RobustKind kind, double d, double sigma) {
  const double r2 = (d * d) / (sigma * sigma);
  switch (kind) {
    case RobustKind::Welsch:
      return std::exp(-0.5 * r2);
    case RobustKind::GemanMcClure:
      return 1.0 / ((1.0 + r2) * (1.0 + r2));
    case RobustKind::None:
      break;
  }
  return 1.0;
}

// One correspondence found in the parallel step, assembled in the serial one.
struct Match {
  bool kept = false;
  int triangle = -1;  // template→frame: the template vertex; frame→template: deformed triangle
  Vec3 bary = Vec3::Zero();
  Vec3 target = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  double dist = 0.0;
};

// The mean distance of the kept correspondences (infinity if none is kept).
double mean_kept_distance(const std::vector<Match>& matches) {
  double sum = 0.0;
  int kept = 0;
  for (const Match& m : matches)
    if (m.kept) sum += m.dist, ++kept;
  return kept > 0 ? sum / kept : std::numeric_limits<double>::infinity();
}

}  // namespace

Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& A) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0) U.col(2) *= -1.0;
  return U * V.transpose();
}

RawFrame prepare_raw_frame(TriMesh mesh, int max_samples) {
  RawFrame raw;
  if (mesh.num_triangles() == 0) throw InputError("the frame has no triangles");
  raw.reference = std::make_shared<const Reference>(std::move(mesh), SampleKind::Vertices, "frame");
  const TriMesh& m = raw.reference->mesh();
  raw.triangle_normals = triangle_normals(m);
  raw.vertex_normals = vertex_normals(m);
  raw.samples = spread(used_vertices(m), max_samples);
  raw.mean_edge = mean_edge_length(m);
  return raw;
}

struct GraphFit::Impl {
  const TriMesh& templ;
  const DeformationGraph& graph;
  TrackOptions options;
  double h;
  std::vector<int> samples;           // template vertices used as samples
  TriangleBvh bvh;                    // the template's, refitted per iteration
  Csr triangle_nodes;                 // distinct nodes of each triangle's corners
  std::vector<int> block_offsets{0};  // per node j: blocks (j, k ≥ j)
  std::vector<int> block_cols;        // k of each block
  BlockCholesky analysed;             // the solver, its pattern analysed once
  // Solvers with their scratch memory between fits (taken by a fit, then given back).
  mutable std::mutex spare_mutex;
  mutable std::vector<std::unique_ptr<BlockCholesky>> spare;

  Impl(const TriMesh& t, const DeformationGraph& g, const TrackOptions& o, double mean_edge)
      : templ(t), graph(g), options(o), h(mean_edge), bvh(t) {
    samples = spread(used_vertices(templ), options.samples);
    build_pattern();
  }

  int block(int j, int k) const {
    if (j > k) std::swap(j, k);
    for (int b = block_offsets[j]; b < block_offsets[j + 1]; ++b)
      if (block_cols[b] == k) return b;
    return -1;
  }

  void build_pattern() {
    const int N = graph.num_nodes();
    std::vector<std::vector<int>> nbr(N);
    std::vector<int> local;
    for (int t = 0; t < templ.num_triangles(); ++t) {
      local.clear();
      for (int c = 0; c < 3; ++c) {
        const int v = templ.F(t, c);
        for (int k = graph.begin(v); k < graph.end(v); ++k) local.push_back(graph.node(k));
      }
      std::sort(local.begin(), local.end());
      local.erase(std::unique(local.begin(), local.end()), local.end());
      triangle_nodes.data.insert(triangle_nodes.data.end(), local.begin(), local.end());
      triangle_nodes.offsets.push_back(static_cast<int>(triangle_nodes.data.size()));
      for (size_t a = 0; a < local.size(); ++a)
        for (size_t b = a; b < local.size(); ++b) nbr[local[a]].push_back(local[b]);
    }
    for (int j = 0; j < N; ++j) nbr[j].push_back(j);
    for (const auto& e : graph.edges()) nbr[e[0]].push_back(e[1]);
    for (int j = 0; j < N; ++j) {
      auto& r = nbr[j];
      std::sort(r.begin(), r.end());
      r.erase(std::unique(r.begin(), r.end()), r.end());
      block_cols.insert(block_cols.end(), r.begin(), r.end());
      block_offsets.push_back(static_cast<int>(block_cols.size()));
    }
    analysed = BlockCholesky(N, 6, block_offsets, block_cols);
  }

  std::unique_ptr<BlockCholesky> take_solver() const {
    const std::lock_guard<std::mutex> lock(spare_mutex);
    if (spare.empty()) return std::make_unique<BlockCholesky>(analysed);
    std::unique_ptr<BlockCholesky> solver = std::move(spare.back());
    spare.pop_back();
    return solver;
  }
  void give_back(std::unique_ptr<BlockCholesky> solver) const {
    const std::lock_guard<std::mutex> lock(spare_mutex);
    spare.push_back(std::move(solver));
  }

  // Adds the Gauss-Newton terms of e(X)ᵀ M e(X), e = Σ_s X_{node_s} q_s + e_const, at the
  // current maps X: e's value there is e0, its Jacobian for node s's update (ω, δt) (node map
  // R exp([ω]×), t + δt) is J_s = [−R [q_s.head]× | q_s[3] I] (3×6).
  void add_term(std::vector<Block>& blocks, Eigen::VectorXd& rhs, const std::vector<NodeMap>& X,
                const int* nodes, const Eigen::Vector4d* q, int count, const Eigen::Matrix3d& M,
                const Vec3& e0) const {
    Eigen::Matrix<double, 3, 6> J[64];
    for (int a = 0; a < count; ++a) {
      const Vec3 d = q[a].head<3>();
      Eigen::Matrix3d cross;
      cross << 0, -d.z(), d.y(), d.z(), 0, -d.x(), -d.y(), d.x(), 0;
      J[a].leftCols<3>() = -X[nodes[a]].leftCols<3>() * cross;
      J[a].rightCols<3>() = q[a][3] * Eigen::Matrix3d::Identity();
    }
    const Vec3 Me = M * e0;
    for (int a = 0; a < count; ++a) {
      rhs.segment<6>(6 * nodes[a]) -= J[a].transpose() * Me;
      const Eigen::Matrix<double, 6, 3> JM = J[a].transpose() * M;
      for (int b = 0; b < count; ++b) {
        if (nodes[a] > nodes[b]) continue;
        blocks[block(nodes[a], nodes[b])] += JM * J[b];
      }
    }
  }

  FitResult fit(const RawFrame& raw, std::vector<NodeMap> X, const FitSchedule& schedule) const;
};

namespace {

Eigen::Matrix3d rotation_of(const Vec3& w) {
  const double angle = w.norm();
  if (angle < 1e-14) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

}  // namespace

FitResult GraphFit::Impl::fit(const RawFrame& raw, std::vector<NodeMap> X,
                              const FitSchedule& schedule) const {
  const int N = graph.num_nodes();
  const int num_blocks = static_cast<int>(block_cols.size());
  const double cos_max = std::cos(options.max_normal_angle * M_PI / 180.0);
  const double spacing2 = std::pow(options.node_spacing * h, 2);
  for (NodeMap& x : X) x.leftCols<3>() = nearest_rotation(x.leftCols<3>());
  TriangleBvh tree = bvh;
  std::unique_ptr<BlockCholesky> solver = take_solver();
  std::vector<Block> blocks(num_blocks);
  Eigen::VectorXd rhs(6 * N);
  std::vector<Match> forward(samples.size()), backward(raw.samples.size());
  FitResult result;

  const double sigma_start = options.robust_scale * h * schedule.scale;
  const int stages = options.stages;
  // The fit's budget is `iterations` per stage run; the last stage takes what the earlier ones
  // left. With `small_motion`, a frame whose first correspondences lie that close is near its fit
  // already, and its coarse stages take one iteration each: on captures, coarse stages run to
  // their share (strong graph term, wide σ) slide such a fit along the surface, and the last
  // stage does not win that back. On smooth generated surfaces the coarse stages are what
  // carries tangential motion, so it is off by default (docs/tracking.md, "The schedule").
  const int first_stage = std::min(schedule.first_stage, stages - 1);
  const int budget = (stages - first_stage) * options.iterations;
  int used = 0;
  bool first = true, small = false;
  for (int stage = first_stage; stage < stages; ++stage) {
    const bool last = stage == stages - 1;
    const double f = stages > 1 ? static_cast<double>(stage) / (stages - 1) : 1.0;
    const double lambda =
        options.regularizer * std::pow(options.regularizer_final / options.regularizer, f);
    const double sigma =
        std::max(options.robust_scale_final * h, sigma_start * std::pow(0.5, stage));
    const double max_dist = options.max_distance * sigma;
    const int share = last ? budget - used : options.iterations;
    for (int it = 0; it < (small && !last ? 1 : share); ++it) {
      ++used;
      const Positions V = graph.deform(X);
      tree.refit(V);
      const TriMesh deformed{V, templ.F};
      const Positions vn = vertex_normals(deformed);
      const Positions tn = triangle_normals(deformed);
      tbb::parallel_for(size_t(0), samples.size(), [&](size_t s) {
        Match& m = forward[s];
        const int v = samples[s];
        const SurfacePoint p =
            raw.reference->bvh().closest(V.row(v).transpose(), max_dist * max_dist);
        m.kept = p.triangle >= 0 && vn.row(v).dot(raw.triangle_normals.row(p.triangle)) >= cos_max;
        if (!m.kept) return;
        m.triangle = v;
        m.target = p.point;
        m.normal = raw.triangle_normals.row(p.triangle).transpose();
        m.dist = std::sqrt(p.dist2);
      });
      tbb::parallel_for(size_t(0), raw.samples.size(), [&](size_t s) {
        Match& m = backward[s];
        const int w = raw.samples[s];
        const Vec3 x = raw.reference->mesh().V.row(w).transpose();
        const SurfacePoint p = tree.closest(x, max_dist * max_dist);
        m.kept = p.triangle >= 0 && tn.row(p.triangle).dot(raw.vertex_normals.row(w)) >= cos_max;
        if (!m.kept) return;
        m.triangle = p.triangle;
        m.bary = p.bary;
        m.target = x;
        m.normal = raw.vertex_normals.row(w).transpose();
        m.dist = std::sqrt(p.dist2);
      });

      if (first) {
        first = false;
        small = mean_kept_distance(forward) < options.small_motion * h;
      }
      for (Block& B : blocks) B.setZero();
      rhs.setZero();
      const double per_node = static_cast<double>(N) / (samples.size() + raw.samples.size());
      const double eps = options.point_weight;
      int kept = 0;
      int nodes[64];
      Eigen::Vector4d q[64];
      auto matrix = [&](const Match& m) {
        const double w = per_node * robust_weight(options.robust, m.dist, sigma) / (h * h);
        return Eigen::Matrix3d(w * ((1.0 - eps) * m.normal * m.normal.transpose() +
                                    eps * Eigen::Matrix3d::Identity()));
      };
      for (const Match& m : forward) {
        if (!m.kept) continue;
        ++kept;
        const int v = m.triangle;
        int count = 0;
        for (int k = graph.begin(v); k < graph.end(v); ++k, ++count) {
          nodes[count] = graph.node(k);
          q[count] = graph.coefficient(k);
        }
        add_term(blocks, rhs, X, nodes, q, count, matrix(m), V.row(v).transpose() - m.target);
      }
      for (const Match& m : backward) {
        if (!m.kept) continue;
        ++kept;
        // The template point under the raw sample, deformed with the node weights of its
        // nearest corner: 6 nodes instead of the union of three corners' (up to 18), at the
        // cost of a Jacobian that is exact only at that corner.
        const int t = m.triangle;
        int corner = 0;
        for (int c = 1; c < 3; ++c)
          if (m.bary[c] > m.bary[corner]) corner = c;
        const int v = templ.F(t, corner);
        Vec3 x = Vec3::Zero(), at = Vec3::Zero();
        for (int c = 0; c < 3; ++c) {
          x += m.bary[c] * templ.V.row(templ.F(t, c)).transpose();
          at += m.bary[c] * V.row(templ.F(t, c)).transpose();
        }
        int count = 0;
        for (int k = graph.begin(v); k < graph.end(v); ++k, ++count) {
          nodes[count] = graph.node(k);
          const double w = graph.weight(k);
          q[count] << w * (x - graph.node_positions().row(nodes[count]).transpose()), w;
        }
        add_term(blocks, rhs, X, nodes, q, count, matrix(m), at - m.target);
      }
      // The graph term, both directions of every edge.
      const Eigen::Matrix3d Mreg = (lambda / spacing2) * Eigen::Matrix3d::Identity();
      for (const auto& e : graph.edges())
        for (int dir = 0; dir < 2; ++dir) {
          const int j = e[dir], k = e[1 - dir];
          const Vec3 gj = graph.node_positions().row(j).transpose();
          const Vec3 gk = graph.node_positions().row(k).transpose();
          nodes[0] = j;
          nodes[1] = k;
          q[0] << gk - gj, 1.0;
          q[1] << 0, 0, 0, -1.0;
          const Vec3 e0 = X[j].leftCols<3>() * (gk - gj) + gj + X[j].col(3) - gk - X[k].col(3);
          add_term(blocks, rhs, X, nodes, q, 2, Mreg, e0);
        }
      // Levenberg-Marquardt damping keeps the step within the linearisation's reach.
      const double damping = 1e-3 * (lambda + 1.0);
      for (int j = 0; j < N; ++j) {
        Block& B = blocks[block(j, j)];
        for (int c = 0; c < 3; ++c) B(c, c) += damping;
        for (int c = 3; c < 6; ++c) B(c, c) += damping / spacing2;
      }
      static_assert(sizeof(Block) == 36 * sizeof(double), "blocks must be contiguous");
      if (!solver->factorize(blocks.data()->data()))
        throw SolverError("deformation graph: the Gauss-Newton system is not definite");
      const Eigen::VectorXd x = solver->solve(rhs);
      if (!x.allFinite())
        throw SolverError("deformation graph: the Gauss-Newton step is not finite");
      double move = 0.0;
      for (int j = 0; j < N; ++j) {
        const Vec3 w = x.segment<3>(6 * j), dt = x.segment<3>(6 * j + 3);
        X[j].leftCols<3>() = X[j].leftCols<3>() * rotation_of(w);
        X[j].col(3) += dt;
        move = std::max(move, dt.norm() + w.norm() * options.node_spacing * h);
      }
      ++result.iterations;
      result.correspondences = kept;
      if (move < 0.01 * h) break;
    }
  }
  give_back(std::move(solver));
  result.V = graph.deform(X);
  result.X = std::move(X);
  return result;
}

GraphFit::GraphFit(const TriMesh& templ, const DeformationGraph& graph, const TrackOptions& options,
                   double mean_edge)
    : impl_(std::make_unique<Impl>(templ, graph, options, mean_edge)) {}
GraphFit::~GraphFit() = default;
GraphFit::GraphFit(GraphFit&&) noexcept = default;

FitResult GraphFit::fit(const RawFrame& raw, std::vector<NodeMap> X0,
                        const FitSchedule& schedule) const {
  return impl_->fit(raw, std::move(X0), schedule);
}

}  // namespace sm
