// The measures of the single-mesh jobs and of `seqmassage measure`: closed-form cases (identical
// meshes, a scaled sphere, a box's sharp edges), the CSV columns, the JSON and the text table.
#include <catch2/catch.hpp>
#include <sstream>

#include "io/csv.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "geometry/measures.hpp"
#include "pipeline/mesh_jobs/mesh_report.hpp"
#include "support/job_meshes.hpp"

using namespace sm;
using Catch::Matchers::Contains;

namespace {

std::vector<std::string> split(const std::string& line, char sep = ',') {
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, sep);) cells.push_back(cell);
  if (!line.empty() && line.back() == sep) cells.emplace_back();
  return cells;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out = split(text, '\n');
  if (!out.empty() && out.back().empty()) out.pop_back();  // the last line's line break
  return out;
}

}  // namespace

TEST_CASE("feature edges: the edges of a box are sharp, its faces flat") {
  const TriMesh box = make_box(4, 2.0, 1.0, 1.5);
  const FeatureEdges f = find_feature_edges(box, 30.0);
  CHECK(f.size() == 12 * 4);
  for (double angle : f.dihedral_degrees) CHECK(angle == Approx(90.0).margin(1e-9));
  for (const auto& e : f.vertices) CHECK(e[0] < e[1]);
  CHECK(find_feature_edges(box, 95.0).size() == 0);
  CHECK(find_feature_edges(make_icosphere(3, 1.0), 30.0).size() == 0);
  // An open grid has boundary edges, which are not feature edges.
  CHECK(find_feature_edges(make_grid(4, 4, 1.0, 1.0), 1.0).size() == 0);
  CHECK(dihedral_degrees(box.V, box.F, f.triangles[0][0], f.triangles[0][1]) ==
        Approx(90.0).margin(1e-9));
}

TEST_CASE("a mesh measured against itself: every distance is exactly zero") {
  const TriMesh box = make_box(3, 2.0, 1.0, 1.5);
  const MeasureOptions options;
  const MeasureReference ref(box, options);
  const MeshMeasures m = measure_mesh(box, ref, &box.V);
  CHECK(m.vertices == box.num_vertices());
  CHECK(m.triangles == box.num_triangles());
  CHECK(m.to_reference.max == 0.0);
  CHECK(m.from_reference.max == 0.0);
  CHECK(m.to_reference.samples == 0);
  CHECK(m.hausdorff == 0.0);
  CHECK(m.diagonal == Approx(std::sqrt(4.0 + 1.0 + 2.25)));
  CHECK(m.radius_ratio.min == Approx(ref.radius_ratio().min));
  REQUIRE(m.shear);
  CHECK(m.shear->summary.max == 0.0);
  CHECK(m.shear->counts.front() == box.num_triangles());
  CHECK(m.features.edges == 36);
  CHECK(m.features.distance.max == 0.0);
  REQUIRE(m.features.dihedral_change_max);
  CHECK(*m.features.dihedral_change_max == Approx(0.0).margin(1e-9));
  CHECK(*m.features.flattened == 0);
}

TEST_CASE("a sphere scaled by 1.1 against the sphere: closed-form distances and shear") {
  const TriMesh sphere = make_icosphere(3, 1.0);
  TriMesh big = sphere;
  big.V *= 1.1;
  const MeasureReference ref(sphere, MeasureOptions{});
  const MeshMeasures m = measure_mesh(big, ref, &sphere.V);
  // Every vertex of the big sphere is 0.1 from its own vertex on the small one, the nearest point.
  CHECK(m.to_reference.max == Approx(0.1).epsilon(1e-9));
  // The other way, the big sphere's faces around a vertex come a little closer than its vertex.
  CHECK(m.from_reference.max <= 0.1);
  CHECK(m.from_reference.max > 0.09);
  CHECK(m.to_reference.mean > 0.09);
  CHECK(m.to_reference.mean <= 0.1 + 1e-12);
  CHECK(m.to_reference.samples > 8 * sphere.num_triangles() / 2);
  CHECK(m.hausdorff == Approx(0.1).epsilon(1e-9));
  CHECK(m.diagonal == Approx(2.2 * std::sqrt(3.0)).epsilon(1e-2));
  CHECK(m.hausdorff_rel == Approx(m.hausdorff / m.diagonal));
  CHECK(m.to_reference.max_rel == Approx(m.to_reference.max / m.diagonal));
  CHECK(m.radius_ratio.min == Approx(ref.radius_ratio().min).epsilon(1e-12));  // similar shapes
  REQUIRE(m.shear);
  const double d = 1.1 + 1.0 / 1.1 - 2.0;  // eq. 8 for a uniform scaling by 1.1
  CHECK(m.shear->summary.max == Approx(d).epsilon(1e-9));
  CHECK(m.shear->summary.mean == Approx(d).epsilon(1e-9));
  CHECK(m.shear->counts[0] == sphere.num_triangles());  // 0.0091 < 0.01
  CHECK(m.features.edges == 0);
}

TEST_CASE("measures.adaptive: the same peak distance from a fraction of the samples") {
  const TriMesh sphere = make_icosphere(3, 1.0);
  TriMesh bumped = sphere;
  bumped.V.row(7) *= 1.2;  // one vertex 0.2 off the sphere: the peak is there
  MeasureOptions adaptive;
  adaptive.adaptive = true;
  const MeshMeasures uniform = measure_mesh(bumped, MeasureReference(sphere, MeasureOptions{}));
  const MeshMeasures refined = measure_mesh(bumped, MeasureReference(sphere, adaptive));
  CHECK(uniform.to_reference.max == Approx(0.2).epsilon(1e-9));
  CHECK(refined.to_reference.max == uniform.to_reference.max);
  CHECK(refined.to_reference.samples * 2 < uniform.to_reference.samples);
  CHECK(refined.from_reference.samples * 2 < uniform.from_reference.samples);
  CHECK(refined.to_reference.refined > 0);
}

TEST_CASE("a corner moved off a box's edge: features distance and dihedral change see it") {
  const test::Box b;
  const TriMesh box = make_box(4, b.sx, b.sy, b.sz);
  TriMesh moved = box;
  // The vertex in the middle of the edge x = 0, y = 0 is pushed into the box.
  int v = -1;
  for (int i = 0; i < box.num_vertices(); ++i)
    if (box.V(i, 0) == 0.0 && box.V(i, 1) == 0.0 && std::abs(box.V(i, 2) - 0.75) < 1e-12) v = i;
  REQUIRE(v >= 0);
  moved.V.row(v) += Eigen::RowVector3d(0.1, 0.1, 0.0);
  const MeasureReference ref(box, MeasureOptions{});
  const MeshMeasures m = measure_mesh(moved, ref);
  CHECK_FALSE(m.shear);
  CHECK(m.features.edges == 48);
  // The edge's old midpoint is off the dented surface, by less than the vertex moved (0.1·√2).
  CHECK(m.features.distance.max > 0.03);
  CHECK(m.features.distance.max <= 0.1 * std::sqrt(2.0) + 1e-12);
  CHECK(m.features.distance.max_rel == Approx(m.features.distance.max / m.diagonal));
  REQUIRE(m.features.dihedral_change_max);
  CHECK(*m.features.dihedral_change_max > 1.0);
  CHECK(*m.features.flattened == 0);  // a dent, the crease keeps its angle
  // The moved vertex is 0.1 inside both faces; nothing is farther than it moved.
  CHECK(m.to_reference.max == Approx(0.1).epsilon(1e-9));
  CHECK(m.hausdorff <= 0.1 * std::sqrt(2.0) + 1e-12);
  // Another connectivity: no dihedral comparison.
  const MeshMeasures other = measure_mesh(make_box(3, b.sx, b.sy, b.sz), ref);
  CHECK_FALSE(other.features.dihedral_change_max);
  CHECK(other.features.distance.max == Approx(0.0).margin(1e-12));
}

TEST_CASE("a box blown up into a ball: every feature edge is flattened") {
  const TriMesh box = make_box(4, 2.0, 2.0, 2.0);
  TriMesh ball = box;
  for (int i = 0; i < ball.num_vertices(); ++i)
    ball.V.row(i) = (box.V.row(i) - Eigen::RowVector3d(1, 1, 1)).normalized();
  ball.V.rowwise() += Eigen::RowVector3d(1, 1, 1);
  const MeshMeasures m = measure_mesh(ball, MeasureReference(box, MeasureOptions{}));
  REQUIRE(m.features.flattened);
  CHECK(*m.features.flattened == 48);
  CHECK(*m.features.dihedral_change_max > 45.0);
  CHECK(m.features.distance.max > 0.2);
}

TEST_CASE("measures.csv has the documented columns, empty cells where a measure does not apply") {
  MeasureOptions options;
  options.shear_bins = {0.0, 0.1, INFINITY};
  const std::vector<std::string> columns = measure_columns(options);
  CHECK(columns.front() == "stage");
  for (const char* name :
       {"dist_mesh_to_ref_max", "dist_mesh_to_ref_rms_rel", "dist_ref_to_mesh_mean",
        "dist_ref_to_mesh_samples", "hausdorff", "hausdorff_rel", "radius_ratio_min",
        "radius_ratio_mean", "shear_max", "shear_mean", "shear_hist_0", "shear_hist_0.1",
        "feature_edges", "feature_dist_max_rel", "dihedral_change_max", "features_flattened"})
    CHECK(std::find(columns.begin(), columns.end(), name) != columns.end());
  CHECK(std::find(columns.begin(), columns.end(), "shear_hist_inf") == columns.end());

  const TriMesh sphere = make_icosphere(2, 1.0);
  TriMesh big = sphere;
  big.V *= 1.2;
  const MeasureReference ref(sphere, options);
  const MeshMeasures with_shear = measure_mesh(big, ref, &sphere.V);
  const MeshMeasures without = measure_mesh(big, ref);
  const std::string csv = format_measures_csv(
      {{"before", "a.obj", "b.obj", &with_shear}, {"after", "a.obj", "b.obj", &without}}, options);
  const auto rows = lines(csv);
  REQUIRE(rows.size() == 3);
  CHECK(split(rows[0]) == columns);
  const auto first = split(rows[1]), second = split(rows[2]);
  REQUIRE(first.size() == columns.size());
  REQUIRE(second.size() == columns.size());
  auto cell = [&](const std::vector<std::string>& row, const std::string& name) {
    return row[std::find(columns.begin(), columns.end(), name) - columns.begin()];
  };
  CHECK(cell(first, "stage") == "before");
  CHECK(cell(first, "mesh") == "a.obj");
  CHECK(std::stod(cell(first, "hausdorff")) == Approx(0.2).epsilon(1e-9));
  CHECK(cell(first, "shear_hist_0") == std::to_string(sphere.num_triangles()));
  CHECK(cell(first, "shear_hist_0.1") == "0");
  CHECK(cell(second, "shear_max").empty());
  CHECK(cell(second, "shear_hist_0").empty());
  CHECK(cell(first, "dihedral_change_max") == "0");  // same connectivity, no feature edges
}

TEST_CASE("measures as JSON and as a text table") {
  const TriMesh sphere = make_icosphere(2, 1.0);
  TriMesh big = sphere;
  big.V *= 1.2;
  const MeasureReference ref(sphere, MeasureOptions{});
  const MeshMeasures before = measure_mesh(big, ref, &sphere.V);
  TriMesh closer = sphere;
  closer.V *= 1.05;
  const MeshMeasures after = measure_mesh(closer, ref, &sphere.V);

  const nlohmann::json j = measures_json(before);
  CHECK(j["hausdorff"].get<double>() == Approx(0.2).epsilon(1e-9));
  CHECK(j["dist_mesh_to_ref"]["max"].get<double>() == Approx(0.2).epsilon(1e-9));
  CHECK(j["dist_ref_to_mesh"].contains("rms_rel"));
  CHECK(j["radius_ratio"].contains("min"));
  CHECK(j["shear"]["histogram"]["bins"].back() == "inf");
  CHECK(j["shear"]["histogram"]["counts"].size() == j["shear"]["histogram"]["bins"].size() - 1);
  CHECK(j["features"]["edges"] == 0);
  CHECK(j["features"]["dihedral_change_max"] == 0.0);
  CHECK(measures_json(measure_mesh(big, ref))["shear"].is_null());

  const QualitySummary q = ref.radius_ratio();
  const std::string table = format_measures_table(
      {{"before", "m.obj", "n.obj", &before}, {"after", "m.obj", "n.obj", &after}}, &q, "t.obj");
  for (const char* text :
       {"M = m.obj (162 vertices, 320 triangles)", "N = n.obj", "T = t.obj", "M -> N\n  before",
        "N -> M\n", "Hausdorff distance\n", "(-75.0% vs before)", "radius ratio 2r/R of M\n",
        "radius ratio 2r/R of N", "shear against T (eq. 8)", "shear histogram (triangles)",
        "feature edges of N (dihedral angle above 30 degrees): 0"})
    CHECK_THAT(table, Contains(text));
  // One row: the values follow the heading on its line.
  const std::string single = format_measures_table({{"measure", "m.obj", "n.obj", &before}});
  CHECK_THAT(single, Contains("M -> N                      2.0000e-01"));
}

TEST_CASE("triangles.csv: one row per triangle, empty cells where nothing was measured") {
  const TriMesh sphere = make_icosphere(1, 1.0);
  const TriangleMeasures before = measure_triangles(sphere, &sphere.V);
  const TriangleMeasures after = measure_triangles(sphere);
  CHECK(before.shear.size() == sphere.num_triangles());
  CHECK(after.shear.size() == 0);
  const auto rows = lines(format_triangles_csv(before, &before));
  REQUIRE(rows.size() == static_cast<size_t>(sphere.num_triangles()) + 1);
  CHECK(rows[0] == "triangle,radius_ratio_before,radius_ratio_after,shear_before,shear_after");
  CHECK(split(rows[1]).size() == 5);
  CHECK(split(rows[1])[3] == "0");
  const auto failed = lines(format_triangles_csv(after, nullptr));
  CHECK(split(failed[1])[2].empty());
  CHECK(split(failed[1])[3].empty());
}

TEST_CASE("measures refuse invalid input") {
  const TriMesh sphere = make_icosphere(1, 1.0);
  TriMesh bad = sphere;
  bad.V(0, 0) = NAN;
  CHECK_THROWS_AS(MeasureReference(bad, MeasureOptions{}, "bad.obj"), InputError);
  const MeasureReference ref(sphere, MeasureOptions{});
  CHECK_THROWS_AS(measure_mesh(bad, ref), InputError);
  const Positions wrong = Positions::Zero(3, 3);
  CHECK_THROWS_AS(measure_mesh(sphere, ref, &wrong), InputError);
  CHECK_THROWS_AS(MeasureReference(TriMesh{}, MeasureOptions{}), InputError);
}
