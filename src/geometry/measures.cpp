#include "geometry/measures.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/sample_budget.hpp"
#include "core/errors.hpp"
#include "mesh/topology.hpp"

namespace sm {
namespace {

constexpr double kDegrees = 180.0 / M_PI;

double diagonal_of_both(const Positions& a, const Positions& b) {
  if (a.rows() == 0 && b.rows() == 0) return 0.0;
  Eigen::RowVector3d lo, hi;
  if (a.rows() > 0) {
    lo = a.colwise().minCoeff();
    hi = a.colwise().maxCoeff();
  } else {
    lo = b.colwise().minCoeff();
    hi = b.colwise().maxCoeff();
  }
  if (b.rows() > 0) {
    lo = lo.cwiseMin(b.colwise().minCoeff());
    hi = hi.cwiseMax(b.colwise().maxCoeff());
  }
  return (hi - lo).norm();
}

// A feature edge is split into at most this many parts.
constexpr long kMaxFeatureEdgeParts = 1L << 16;

// The points feature_samples takes (below), counted in floating point.
double feature_sample_count(const TriMesh& N, const FeatureEdges& features, double h) {
  std::vector<unsigned char> seen(N.num_vertices(), 0);
  double count = 0.0;
  for (const auto& e : features.vertices) {
    for (int v : e)
      if (!seen[v]) {
        seen[v] = 1;
        count += 1.0;
      }
    const double length = (N.vertex(e[1]) - N.vertex(e[0])).norm();
    count += double(sample_divisions(length, h, kMaxFeatureEdgeParts) - 1);
  }
  return count;
}

// Points along the feature edges of N: every feature vertex once, then the interior points of
// each edge split into ceil(L / h) equal parts.
std::vector<Vec3> feature_samples(const TriMesh& N, const FeatureEdges& features, double h) {
  std::vector<Vec3> points;
  std::vector<unsigned char> seen(N.num_vertices(), 0);
  for (const auto& e : features.vertices)
    for (int v : e)
      if (!seen[v]) {
        seen[v] = 1;
        points.push_back(N.vertex(v));
      }
  for (const auto& e : features.vertices) {
    const Vec3 a = N.vertex(e[0]), d = N.vertex(e[1]) - a;
    const long parts = sample_divisions(d.norm(), h, kMaxFeatureEdgeParts);
    for (long j = 1; j < parts; ++j) points.push_back(a + (double(j) / double(parts)) * d);
  }
  return points;
}

DistanceStats point_distances(const std::vector<Vec3>& points, const TriangleBvh& surface,
                              double diagonal) {
  DistanceStats s;
  if (points.empty()) return s;
  std::vector<double> d(points.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 512),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t i = r.begin(); i != r.end(); ++i)
                        d[i] = std::sqrt(surface.closest(points[i]).dist2);
                    });
  double sum = 0.0, sum2 = 0.0;  // summed in order: deterministic
  for (double x : d) {
    s.max = std::max(s.max, x);
    sum += x;
    sum2 += x * x;
  }
  s.samples = static_cast<long>(d.size());
  s.mean = sum / static_cast<double>(d.size());
  s.rms = std::sqrt(sum2 / static_cast<double>(d.size()));
  if (diagonal > 0.0) {
    s.max_rel = s.max / diagonal;
    s.mean_rel = s.mean / diagonal;
    s.rms_rel = s.rms / diagonal;
  }
  return s;
}

Vec3 unit_normal(const Positions& V, const Triangles& F, int t) {
  const Vec3 a = V.row(F(t, 0)).transpose(), b = V.row(F(t, 1)).transpose(),
             c = V.row(F(t, 2)).transpose();
  const Vec3 n = (b - a).cross(c - a);
  const double len = n.norm();
  return len > 0.0 && std::isfinite(len) ? Vec3(n / len) : Vec3::Zero();
}

}  // namespace

double dihedral_degrees(const Positions& V, const Triangles& F, int t, int u) {
  const Vec3 nt = unit_normal(V, F, t), nu = unit_normal(V, F, u);
  if (nt.isZero() || nu.isZero()) return 0.0;
  // atan2 of |cross| and dot: accurate near 0° and 180°, unlike acos of the dot product.
  return std::atan2(nt.cross(nu).norm(), nt.dot(nu)) * kDegrees;
}

FeatureEdges find_feature_edges(const TriMesh& mesh, double threshold_degrees) {
  validate_mesh(mesh, "find_feature_edges");
  FeatureEdges f;
  f.threshold_degrees = threshold_degrees;
  const Topology topo = build_topology(mesh);
  for (int t = 0; t < mesh.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int u = topo.triangle_neighbours[t][k];
      if (u < t) continue;  // boundary or non-manifold (-1), or seen from u already
      const Vec3 nt = unit_normal(mesh.V, mesh.F, t), nu = unit_normal(mesh.V, mesh.F, u);
      if (nt.isZero() || nu.isZero()) continue;
      const double angle = dihedral_degrees(mesh.V, mesh.F, t, u);
      if (!(angle > threshold_degrees)) continue;
      const int a = mesh.F(t, k), b = mesh.F(t, (k + 1) % 3);
      f.vertices.push_back({std::min(a, b), std::max(a, b)});
      f.triangles.push_back({t, u});
      f.dihedral_degrees.push_back(angle);
    }
  return f;
}

MeasureReference::MeasureReference(TriMesh mesh, const MeasureOptions& options, const char* name)
    : mesh_(std::move(mesh)), options_(options) {
  validate_mesh(mesh_, name);
  if (mesh_.num_triangles() == 0)
    throw InputError(std::string(name) + ": the mesh has no triangles");
  bvh_ = TriangleBvh(mesh_);
  features_ = find_feature_edges(mesh_, options_.feature_angle);
  radius_ratio_ = summarize_quality(sm::radius_ratio(mesh_));
}

MeshMeasures measure_mesh(const TriMesh& mesh, const MeasureReference& reference,
                          const Positions* shear_template) {
  validate_mesh(mesh, "measured mesh");
  const TriMesh& N = reference.mesh();
  const MeasureOptions& o = reference.options();
  MeshMeasures m;
  m.vertices = mesh.num_vertices();
  m.triangles = mesh.num_triangles();
  m.diagonal = diagonal_of_both(mesh.V, N.V);
  m.radius_ratio = summarize_quality(radius_ratio(mesh));

  const bool same_connectivity =
      mesh.F.rows() == N.F.rows() && mesh.V.rows() == N.V.rows() && mesh.F == N.F;
  const bool identical = same_connectivity && mesh.V == N.V;
  DistanceOptions sampling;
  sampling.spacing = o.spacing;
  sampling.adaptive = o.adaptive;
  if (!identical) {  // the spacing within the budget, both ways and on N's feature edges
    check_distance_samples(mesh, sampling, "the measured mesh");
    check_distance_samples(N, sampling, "the reference");
    check_sample_budget(
        feature_sample_count(N, reference.features(), o.spacing * mean_edge_length(N)),
        N.num_triangles(), o.spacing, false, "the reference's feature edges");
  }
  const TriangleBvh mesh_bvh(mesh);
  if (!identical) {
    m.to_reference = one_sided_distance(mesh, reference.bvh(), sampling);
    m.from_reference = one_sided_distance(N, mesh_bvh, sampling);
  }
  m.hausdorff = symmetric_hausdorff(m.to_reference, m.from_reference);
  m.hausdorff_rel = m.diagonal > 0.0 ? m.hausdorff / m.diagonal : 0.0;

  if (shear_template) {
    if (shear_template->rows() != mesh.V.rows())
      throw InputError("shear template: " + std::to_string(shear_template->rows()) +
                       " vertices, but the measured mesh has " + std::to_string(mesh.V.rows()));
    const Eigen::VectorXd shear = shear_distortion(*shear_template, mesh.V, mesh.F);
    ShearMeasures s;
    s.summary = summarize_distortion(shear);
    s.bins = o.shear_bins;
    s.counts = histogram(shear, s.bins);
    m.shear = std::move(s);
  }

  const FeatureEdges& features = reference.features();
  m.features.threshold_degrees = features.threshold_degrees;
  m.features.edges = features.size();
  if (!identical) {
    const double h = o.spacing * mean_edge_length(N);
    m.features.distance = point_distances(feature_samples(N, features, h), mesh_bvh, m.diagonal);
  }
  if (same_connectivity) {
    double max_change = 0.0, sum = 0.0;
    int flattened = 0;
    for (int e = 0; e < features.size(); ++e) {
      const double after =
          dihedral_degrees(mesh.V, mesh.F, features.triangles[e][0], features.triangles[e][1]);
      const double change = std::abs(after - features.dihedral_degrees[e]);
      max_change = std::max(max_change, change);
      sum += change;
      flattened += after < 0.5 * features.dihedral_degrees[e];
    }
    m.features.dihedral_change_max = max_change;
    m.features.dihedral_change_mean = features.size() > 0 ? sum / features.size() : 0.0;
    m.features.flattened = flattened;
  }
  return m;
}

TriangleMeasures measure_triangles(const TriMesh& mesh, const Positions* shear_template) {
  TriangleMeasures t;
  t.radius_ratio = radius_ratio(mesh);
  if (shear_template) t.shear = shear_distortion(*shear_template, mesh.V, mesh.F);
  return t;
}

}  // namespace sm
