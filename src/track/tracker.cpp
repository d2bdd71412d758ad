#include "track/tracker.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "geometry/shear.hpp"
#include "core/errors.hpp"
#include "core/timing.hpp"
#include "mesh/topology.hpp"

namespace sm {

namespace {

struct Spread {
  double mean = 0, p99 = 0, max = 0;
};

Spread spread_of(std::vector<double> d, double unit) {
  Spread s;
  if (d.empty()) return s;
  double total = 0;
  for (double x : d) total += x;
  s.mean = total / d.size() / unit;
  const size_t k = std::min(d.size() - 1, static_cast<size_t>(std::ceil(0.99 * d.size())) - 1);
  std::nth_element(d.begin(), d.begin() + k, d.end());
  s.p99 = d[k] / unit;
  s.max = *std::max_element(d.begin(), d.end()) / unit;
  return s;
}

// The node maps of one rigid motion x → R x + t.
std::vector<NodeMap> rigid_maps(const DeformationGraph& graph, const Eigen::Matrix3d& R,
                                const Vec3& t) {
  std::vector<NodeMap> X(graph.num_nodes());
  for (int j = 0; j < graph.num_nodes(); ++j) {
    const Vec3 g = graph.node_positions().row(j).transpose();
    X[j].leftCols<3>() = R;
    X[j].col(3) = R * g + t - g;
  }
  return X;
}

// The motion from X2 to X1 applied once more to X1: node positions move on by their last step,
// node maps turn on by their last rotation.
std::vector<NodeMap> continue_motion(const DeformationGraph& graph, const std::vector<NodeMap>& X1,
                                     const std::vector<NodeMap>& X2) {
  std::vector<NodeMap> X(X1.size());
  for (size_t j = 0; j < X1.size(); ++j) {
    const Eigen::Matrix3d turn = nearest_rotation(X1[j].leftCols<3>()) *
                                 nearest_rotation(X2[j].leftCols<3>()).transpose();
    X[j].leftCols<3>() = turn * X1[j].leftCols<3>();
    X[j].col(3) = 2.0 * X1[j].col(3) - X2[j].col(3);
  }
  (void)graph;
  return X;
}

// A rigid motion taking the template near the raw frame: centroids matched, then rigid ICP
// (point to point, both directions, Kabsch).
std::vector<NodeMap> rigid_alignment(const TriMesh& templ, const DeformationGraph& graph,
                                     const RawFrame& raw, double h) {
  const TriMesh& N = raw.reference->mesh();
  const Vec3 ct = templ.V.colwise().mean().transpose();
  const Vec3 cn = N.V.colwise().mean().transpose();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Vec3 t = cn - ct;
  TriangleBvh tree(templ);
  const int step_t = std::max(1, templ.num_vertices() / 2000);
  const int step_n = std::max(1, N.num_vertices() / 2000);
  for (int it = 0; it < 30; ++it) {
    Positions V = (templ.V * R.transpose()).rowwise() + t.transpose();
    tree.refit(V);
    std::vector<Vec3> a, b;  // a: points of the moved template, b: their partners on N
    for (int v = 0; v < templ.num_vertices(); v += step_t) {
      const SurfacePoint p = raw.reference->bvh().closest(V.row(v).transpose());
      if (p.triangle < 0) continue;
      a.push_back(templ.V.row(v).transpose());
      b.push_back(p.point);
    }
    for (int w = 0; w < N.num_vertices(); w += step_n) {
      const SurfacePoint p = tree.closest(N.V.row(w).transpose());
      if (p.triangle < 0) continue;
      const auto& f = templ.F.row(p.triangle);
      a.push_back(p.bary[0] * templ.V.row(f[0]).transpose() +
                  p.bary[1] * templ.V.row(f[1]).transpose() +
                  p.bary[2] * templ.V.row(f[2]).transpose());
      b.push_back(N.V.row(w).transpose());
    }
    Vec3 ma = Vec3::Zero(), mb = Vec3::Zero();
    for (size_t k = 0; k < a.size(); ++k) ma += a[k], mb += b[k];
    ma /= static_cast<double>(a.size());
    mb /= static_cast<double>(b.size());
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    for (size_t k = 0; k < a.size(); ++k) C += (b[k] - mb) * (a[k] - ma).transpose();
    const Eigen::Matrix3d Rn = nearest_rotation(C);
    const Vec3 tn = mb - Rn * ma;
    const double change = (Rn - R).norm() * templ.V.norm() / std::sqrt(templ.V.rows()) +
                          (tn - t).norm();
    R = Rn;
    t = tn;
    if (change < 1e-3 * h) break;
  }
  return rigid_maps(graph, R, t);
}

}  // namespace

FitFigures measure_fit(const TriMesh& templ, const Positions& V, const RawFrame& raw, double h) {
  FitFigures f;
  const Reference& ref = *raw.reference;
  const TriMesh tracked{V, templ.F};
  std::vector<double> to(V.rows()), from(ref.mesh().num_vertices(), 0.0);
  std::vector<int> folded(templ.num_triangles(), 0);
  const Positions tn = triangle_normals(tracked);
  tbb::parallel_for(0, static_cast<int>(V.rows()), [&](int v) {
    to[v] = std::sqrt(ref.bvh().closest(V.row(v).transpose()).dist2);
  });
  tbb::parallel_for(0, templ.num_triangles(), [&](int t) {
    const Vec3 c = (V.row(templ.F(t, 0)) + V.row(templ.F(t, 1)) + V.row(templ.F(t, 2))) / 3.0;
    const SurfacePoint p = ref.bvh().closest(c);
    folded[t] = p.triangle >= 0 && tn.row(t).dot(raw.triangle_normals.row(p.triangle)) < 0;
  });
  TriangleBvh tree(tracked);
  std::vector<int> used;
  {
    std::vector<uint8_t> in(ref.mesh().num_vertices(), 0);
    for (int t = 0; t < ref.mesh().num_triangles(); ++t)
      for (int c = 0; c < 3; ++c) in[ref.mesh().F(t, c)] = 1;
    for (int w = 0; w < ref.mesh().num_vertices(); ++w)
      if (in[w]) used.push_back(w);
  }
  from.resize(used.size());
  tbb::parallel_for(0, static_cast<int>(used.size()), [&](int k) {
    from[k] = std::sqrt(tree.closest(ref.mesh().V.row(used[k]).transpose()).dist2);
  });
  const Spread a = spread_of(std::move(to), h), b = spread_of(std::move(from), h);
  f.to_raw_mean = a.mean, f.to_raw_p99 = a.p99, f.to_raw_max = a.max;
  f.from_raw_mean = b.mean, f.from_raw_p99 = b.p99, f.from_raw_max = b.max;
  for (int x : folded) f.folded += x;
  const DistortionSummary shear = summarize_distortion(shear_distortion(templ.V, V, templ.F));
  f.shear_mean = shear.mean;
  f.shear_max = shear.max;
  return f;
}

struct Tracker::State {
  TriMesh templ;
  TrackOptions options;
  double h = 0;
  Topology topology;
  DeformationGraph graph;
  std::optional<GraphFit> fit;
  std::optional<Massager> massager;
  std::vector<NodeMap> prev, prev2, last_good;
  int history = 0;  // fits in prev (1) and prev2 (2) that belong to consecutive good frames
};

Tracker::Tracker(TriMesh templ, TrackOptions options, MassageOptions massage)
    : s_(std::make_unique<State>()) {
  try {
    check_option_ranges(options);
  } catch (const OptionError& e) {
    throw e.under("track");
  }
  validate_mesh(templ, "template");
  if (templ.num_triangles() == 0) throw InputError("template: the mesh has no triangles");
  s_->templ = std::move(templ);
  s_->options = options;
  s_->h = mean_edge_length(s_->templ);
  if (!(s_->h > 0)) throw InputError("template: the mean edge length is zero");
  s_->topology = build_topology(s_->templ);
  s_->graph = DeformationGraph(s_->templ, s_->topology, options.node_spacing * s_->h,
                               options.node_influences);
  s_->fit.emplace(s_->templ, s_->graph, s_->options, s_->h);
  if (options.refine_iterations > 0) {
    massage.iterations = options.refine_iterations;
    try {
      s_->massager.emplace(s_->templ, massage, "template");
    } catch (const OptionError& e) {
      throw e.under("massage");
    }
  }
  reset();
}

Tracker::~Tracker() = default;
Tracker::Tracker(Tracker&&) noexcept = default;

void Tracker::reset() {
  s_->prev = s_->graph.identity();
  s_->last_good = s_->prev;
  s_->history = 1;
}

void Tracker::restart_from(const std::vector<NodeMap>& X) {
  if (static_cast<int>(X.size()) != s_->graph.num_nodes())
    throw InputError("tracker: the fit to start from has another number of nodes");
  s_->prev = X;
  s_->last_good = X;
  s_->history = 1;
}

const std::vector<NodeMap>& Tracker::last_fit() const { return s_->prev; }
const TriMesh& Tracker::templ() const { return s_->templ; }
double Tracker::mean_edge() const { return s_->h; }
int Tracker::num_nodes() const { return s_->graph.num_nodes(); }
const TrackOptions& Tracker::options() const { return s_->options; }

namespace {

// How far beyond the tolerances the figures are: ≤ 1 within them.
double excess(const FitFigures& f, const TrackOptions& o, int triangles) {
  double e = std::max(f.to_raw_mean, f.from_raw_mean) / o.lost_distance;
  e = std::max(e, std::max(f.to_raw_p99, f.from_raw_p99) / o.lost_distance_p99);
  if (triangles > 0 && f.folded > 0)
    e = std::max(e, (static_cast<double>(f.folded) / triangles) /
                        std::max(o.lost_folded_fraction, 1e-12));
  return e;
}

}  // namespace

TrackFrame Tracker::track(const TriMesh& raw_mesh) {
  State& s = *s_;
  const TrackOptions& o = s.options;
  validate_mesh(raw_mesh, "frame");
  const RawFrame raw = prepare_raw_frame(raw_mesh, o.samples);
  const int m = s.templ.num_triangles();

  struct Attempt {
    FitResult fit;
    TrackFrame frame;
    double excess = 0;
  };
  auto attempt = [&](std::vector<NodeMap> X0, FitSchedule schedule) {
    Attempt a;
    const auto t0 = Clock::now();
    a.fit = s.fit->fit(raw, std::move(X0), schedule);
    a.frame.seconds_register = seconds_since(t0);
    a.frame.iterations = a.fit.iterations;
    a.frame.registered = a.fit.V;
    a.frame.V = a.fit.V;
    const auto t1 = Clock::now();
    if (s.massager) {
      MassageResult r = s.massager->run(a.fit.V, *raw.reference);
      a.frame.refine_ok = r.ok && r.V.allFinite();
      if (a.frame.refine_ok) a.frame.V = std::move(r.V);
    }
    if (o.project) {
      Positions& V = a.frame.V;
      tbb::parallel_for(0, static_cast<int>(V.rows()), [&](int v) {
        const SurfacePoint p = raw.reference->bvh().closest(V.row(v).transpose());
        if (p.triangle >= 0) V.row(v) = p.point.transpose();
      });
    }
    a.frame.seconds_refine = seconds_since(t1);
    a.frame.registration_fit = measure_fit(s.templ, a.frame.registered, raw, s.h);
    a.frame.fit = s.massager || o.project ? measure_fit(s.templ, a.frame.V, raw, s.h)
                                          : a.frame.registration_fit;
    a.excess = excess(a.frame.fit, o, m);
    return a;
  };

  std::vector<NodeMap> start = s.prev;
  if (o.extrapolate && s.history >= 2) start = continue_motion(s.graph, s.prev, s.prev2);
  Attempt best = attempt(std::move(start), {});
  int iterations = best.frame.iterations;
  if (best.excess > 1.0 && o.recover) {
    Attempt wide = attempt(s.last_good, {o.recover_scale, 0});
    iterations += wide.frame.iterations;
    wide.frame.recovery = "last_good";
    if (wide.excess < best.excess) best = std::move(wide);
    if (best.excess > 1.0) {
      Attempt fresh = attempt(rigid_alignment(s.templ, s.graph, raw, s.h), {o.recover_scale, 0});
      iterations += fresh.frame.iterations;
      fresh.frame.recovery = "template";
      if (fresh.excess < best.excess) best = std::move(fresh);
    }
    best.frame.status = best.excess <= 1.0 ? TrackStatus::Recovered : TrackStatus::Lost;
  } else if (best.excess > 1.0) {
    best.frame.status = TrackStatus::Lost;  // without recovery: beyond the tolerances is lost
  }
  best.frame.iterations = iterations;
  if (best.frame.status != TrackStatus::Lost) {
    s.prev2 = std::move(s.prev);
    s.prev = best.fit.X;
    s.last_good = best.fit.X;
    s.history = best.frame.status == TrackStatus::Ok ? std::min(s.history + 1, 2) : 1;
  } else {
    s.prev = s.last_good;  // the next frame starts from the last good fit, without motion
    s.history = 1;
  }
  return std::move(best.frame);
}

}  // namespace sm
