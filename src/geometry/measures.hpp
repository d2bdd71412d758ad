#pragma once
/// The paper's measures of a mesh M against a reference surface N (Tables 1–3): Metro-style
/// one-sided distances both ways and the symmetric Hausdorff distance, the radius ratio of M's
/// triangles, the shear distortion (eq. 8) of M against a template with its connectivity, and how
/// well N's sharp (feature) edges survive on M.
#include <array>
#include <optional>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/distance.hpp"
#include "geometry/quality.hpp"
#include "geometry/shear.hpp"
#include "mesh/mesh.hpp"
#include "geometry/measure_options.hpp"

namespace sm {


/// Interior edges of a mesh whose dihedral angle exceeds a threshold. The dihedral angle of an
/// edge is the angle between the unit normals of its two triangles: 0 on a flat stretch, 90° on
/// the edge of a cube. Boundary and non-manifold edges are never feature edges.
struct FeatureEdges {
  double threshold_degrees = 0.0;
  std::vector<std::array<int, 2>> vertices;   ///< the edge's two vertices, smaller index first
  std::vector<std::array<int, 2>> triangles;  ///< the two triangles that share it
  std::vector<double> dihedral_degrees;       ///< its dihedral angle on the mesh it came from
  int size() const { return static_cast<int>(vertices.size()); }
};

/// Every interior manifold edge of `mesh` with a dihedral angle above `threshold_degrees`, in the
/// order of first appearance (triangle, then local edge). Edges of degenerate triangles (no normal)
/// are left out.
FeatureEdges find_feature_edges(const TriMesh& mesh, double threshold_degrees);

/// Dihedral angle in degrees between triangles t and u of (V, F); 0 if either is degenerate.
double dihedral_degrees(const Positions& V, const Triangles& F, int t, int u);

/// N prepared once for measuring any number of meshes against it: a copy of the mesh, its BVH,
/// its feature edges and its own radius ratio.
class MeasureReference {
 public:
  /// Throws InputError (naming `name`) for an invalid mesh or one without triangles.
  MeasureReference(TriMesh mesh, const MeasureOptions& options, const char* name = "reference");
  const TriMesh& mesh() const { return mesh_; }
  const TriangleBvh& bvh() const { return bvh_; }
  const FeatureEdges& features() const { return features_; }
  QualitySummary radius_ratio() const { return radius_ratio_; }
  const MeasureOptions& options() const { return options_; }

 private:
  TriMesh mesh_;
  MeasureOptions options_;
  TriangleBvh bvh_;
  FeatureEdges features_;
  QualitySummary radius_ratio_;
};

/// Shear distortion of M's triangles against a template with M's connectivity (eq. 8).
struct ShearMeasures {
  DistortionSummary summary;
  std::vector<double> bins;  ///< histogram bin edges (MeasureOptions::shear_bins)
  std::vector<int> counts;   ///< triangles per bin (bins.size() − 1 values)
};

/// How N's feature edges are kept on M.
struct FeatureMeasures {
  double threshold_degrees = 0.0;  ///< MeasureOptions::feature_angle
  int edges = 0;                   ///< N's feature edges
  /// Points along N's feature edges (every feature vertex once, and interior points at most
  /// spacing · mean edge length of N apart) to M's surface; relative values share the diagonal of
  /// the distances below.
  DistanceStats distance;
  /// When M has N's connectivity: |dihedral angle on M − dihedral angle on N| over N's feature
  /// edges, in degrees (max, mean), and how many of them lost more than half their angle
  /// ("flattened").
  std::optional<double> dihedral_change_max, dihedral_change_mean;
  std::optional<int> flattened;
};

struct MeshMeasures {
  int vertices = 0;
  int triangles = 0;
  DistanceStats to_reference;          ///< sampled on M, distances to N
  DistanceStats from_reference;        ///< sampled on N, distances to M
  double hausdorff = 0.0;              ///< max of the two maxima (model units)
  double hausdorff_rel = 0.0;          ///< the same relative to the diagonal of both meshes' box
  double diagonal = 0.0;               ///< bounding-box diagonal of M and N together
  QualitySummary radius_ratio;         ///< of M's triangles
  std::optional<ShearMeasures> shear;  ///< when a template is given
  FeatureMeasures features;
};

/// Measures `mesh` against `reference`; with `shear_template` (positions on mesh.F, n×3), also the
/// shear of every triangle against it. When `mesh` is the reference itself (same positions and
/// triangles), the distances are exactly 0 with 0 samples (not sampled). Deterministic whatever
/// the number of threads. Throws InputError for an invalid mesh or a template of the wrong size.
MeshMeasures measure_mesh(const TriMesh& mesh, const MeasureReference& reference,
                          const Positions* shear_template = nullptr);

/// Per-triangle radius ratio and (with a template) shear of `mesh`, for triangles.csv.
struct TriangleMeasures {
  Eigen::VectorXd radius_ratio;
  Eigen::VectorXd shear;  ///< empty without a template
};
TriangleMeasures measure_triangles(const TriMesh& mesh, const Positions* shear_template = nullptr);

}  // namespace sm
