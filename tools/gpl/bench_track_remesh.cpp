// Builds one data set of the tracking benchmark (docs/tracking-benchmark.md) from a tracked
// sequence (one connectivity, so the truth of every point is known): every chosen frame is
// remeshed on its own with CGAL's isotropic remeshing, with a per-frame random perturbation so
// that no two frames share a triangulation, and the truth of the template (the remeshed first
// frame) is written for every frame.
//
// GPL: CGAL's Polygon Mesh Processing package is GPL-3.0-or-later, so this program is built only
// with -DSEQMASSAGE_BUILD_GPL_BENCH=ON (off by default) and is no part of seqmassage's binaries.
//
//   bench_track_remesh --source FOLDER|FILE.pc2 [--rest rest.obj] --out DIR
//                      [--first 0] [--stride 1] [--count N] [--seed 1] [--iterations 5]
//                      [--length-factor 1.0]
//
// --source is a folder of frame_NNNN.obj sharing one connectivity, or a PC2 point cache with
// --rest, the OBJ giving its triangles. The chosen source frames are first, first + stride, ...
// Output (DIR):
//   raw/frame_NNNN.obj     frame k remeshed on its own (target edge length: the source's mean
//                          edge length at frame `first`, times --length-factor); every vertex is
//                          projected onto source frame k's surface at the end
//   template.obj           raw/frame_0000.obj (the template a tracker starts from)
//   truth/frame_NNNN.obj   the template's connectivity at the true positions on frame k: each
//                          template vertex's closest point on the source's frame `first`
//                          (triangle + barycentric coordinates) carried to source frame k; one
//                          `vn` line per vertex: the unit normal of that source triangle at frame k
//   truth/locations.csv    vertex, triangle, b0, b1, b2 (weights of the triangle's corners in the
//                          source's order), distance (template vertex to the source surface)
//   meta.json              source, frames, seed, target edge length, template's mean edge length
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/random_perturbation.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/mesh_file.hpp"
#include "io/point_cache.hpp"
#include "mesh/mesh.hpp"

namespace fs = std::filesystem;
namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Surface = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Surface>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

namespace {

// The source sequence: its triangles and a way to get frame k's positions.
struct Source {
  sm::Triangles F;
  int frames = 0;
  std::vector<fs::path> obj_frames;  // folder form
  fs::path pc2;                      // point-cache form
  sm::PointCacheHeader header;

  sm::Positions positions(int k) const {
    if (!obj_frames.empty()) return sm::read_mesh(obj_frames[k]).V;
    return sm::decode_point_cache_frame(sm::read_point_cache_frame_bytes(pc2, header, k), header,
                                        k, pc2.string());
  }
};

Source open_source(const fs::path& source, const fs::path& rest) {
  Source s;
  if (fs::is_directory(source)) {
    for (const auto& e : fs::directory_iterator(source))
      if (e.path().extension() == ".obj") s.obj_frames.push_back(e.path());
    std::sort(s.obj_frames.begin(), s.obj_frames.end());
    if (s.obj_frames.empty()) throw std::runtime_error(source.string() + ": no .obj frames");
    s.F = sm::read_mesh(s.obj_frames[0]).F;
    s.frames = static_cast<int>(s.obj_frames.size());
  } else {
    if (rest.empty()) throw std::runtime_error("--rest is needed with a point cache");
    s.pc2 = source;
    s.header = sm::read_point_cache_header(source, sm::PointCacheFormat::Pc2);
    const sm::TriMesh r = sm::read_mesh(rest);
    if (r.num_vertices() != s.header.points)
      throw std::runtime_error(rest.string() + ": vertex count differs from the point cache's");
    s.F = r.F;
    s.frames = s.header.frames;
  }
  return s;
}

Surface to_surface(const sm::Positions& V, const sm::Triangles& F) {
  Surface m;
  std::vector<Surface::Vertex_index> v(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) v[i] = m.add_vertex(Point(V(i, 0), V(i, 1), V(i, 2)));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    if (m.add_face(v[F(f, 0)], v[F(f, 1)], v[F(f, 2)]) == Surface::null_face())
      throw std::runtime_error("triangle " + std::to_string(f) + " is not manifold for CGAL");
  return m;
}

sm::TriMesh to_trimesh(const Surface& m) {
  sm::TriMesh out;
  out.V.resize(m.number_of_vertices(), 3);
  std::vector<int> index(m.num_vertices(), -1);
  int n = 0;
  for (auto v : m.vertices()) {
    const Point& p = m.point(v);
    out.V.row(n) << p.x(), p.y(), p.z();
    index[v] = n++;
  }
  out.F.resize(m.number_of_faces(), 3);
  int f = 0;
  for (auto face : m.faces()) {
    int c = 0;
    for (auto v : CGAL::vertices_around_face(m.halfedge(face), m)) out.F(f, c++) = index[v];
    ++f;
  }
  return out;
}

// Frame k remeshed on its own: remesh, perturb along the surface with the frame's seed, remesh
// again (so the triangulation is its own), then project every vertex onto the source surface.
sm::TriMesh remesh_frame(const sm::Positions& V, const sm::Triangles& F, double length,
                         int iterations, unsigned seed) {
  const Surface source = to_surface(V, F);
  Surface m = source;
  PMP::isotropic_remeshing(faces(m), length, m, CGAL::parameters::number_of_iterations(iterations));
  m.collect_garbage();
  PMP::random_perturbation(vertices(m), m, 0.45 * length,
                           CGAL::parameters::random_seed(seed).do_project(true));
  PMP::isotropic_remeshing(faces(m), length, m, CGAL::parameters::number_of_iterations(2));
  m.collect_garbage();
  Tree tree(faces(source).first, faces(source).second, source);
  tree.accelerate_distance_queries();
  for (auto v : m.vertices()) m.point(v) = tree.closest_point(m.point(v));
  return to_trimesh(m);
}

struct Location {
  int triangle = -1;
  double b[3] = {0, 0, 0};
  double distance = 0;
};

// Barycentric coordinates of p (on or near triangle a, b, c) clamped to the triangle.
void barycentric(const sm::Vec3& p, const sm::Vec3& a, const sm::Vec3& b, const sm::Vec3& c,
                 double out[3]) {
  const sm::Vec3 e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double d20 = d.dot(e0), d21 = d.dot(e1), den = d00 * d11 - d01 * d01;
  double v = den > 0 ? (d11 * d20 - d01 * d21) / den : 0;
  double w = den > 0 ? (d00 * d21 - d01 * d20) / den : 0;
  v = std::max(0.0, v);
  w = std::max(0.0, w);
  if (v + w > 1) {
    const double s = v + w;
    v /= s;
    w /= s;
  }
  out[0] = 1 - v - w;
  out[1] = v;
  out[2] = w;
}

std::vector<Location> locate(const sm::Positions& P, const sm::Positions& V,
                             const sm::Triangles& F) {
  const Surface source = to_surface(V, F);
  Tree tree(faces(source).first, faces(source).second, source);
  tree.accelerate_distance_queries();
  std::vector<Location> out(P.rows());
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Point q(P(i, 0), P(i, 1), P(i, 2));
    const auto hit = tree.closest_point_and_primitive(q);
    Location& l = out[i];
    l.triangle = static_cast<int>(hit.second.idx());
    const sm::Vec3 p = P.row(i).transpose();
    barycentric(p, V.row(F(l.triangle, 0)).transpose(), V.row(F(l.triangle, 1)).transpose(),
                V.row(F(l.triangle, 2)).transpose(), l.b);
    l.distance = std::sqrt(CGAL::to_double(CGAL::squared_distance(q, hit.first)));
  }
  return out;
}

void write_text(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, path);
}

std::string obj_text(const sm::Positions& V, const sm::Triangles& F, const sm::Positions* N) {
  std::string s;
  s.reserve(V.rows() * 80 + F.rows() * 24);
  char line[128];
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    std::snprintf(line, sizeof line, "v %.12g %.12g %.12g\n", V(i, 0), V(i, 1), V(i, 2));
    s += line;
  }
  if (N)
    for (Eigen::Index i = 0; i < N->rows(); ++i) {
      std::snprintf(line, sizeof line, "vn %.9f %.9f %.9f\n", (*N)(i, 0), (*N)(i, 1), (*N)(i, 2));
      s += line;
    }
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    std::snprintf(line, sizeof line, "f %d %d %d\n", F(f, 0) + 1, F(f, 1) + 1, F(f, 2) + 1);
    s += line;
  }
  return s;
}

std::string frame_name(int k) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.obj", k);
  return name;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Remesh a tracked sequence frame by frame and write the tracking truth (GPL, CGAL)"};
  fs::path source_path, rest, out;
  int first = 0, stride = 1, count = -1, iterations = 5;
  unsigned seed = 1;
  double length_factor = 1.0;
  app.add_option("--source", source_path, "folder of OBJ frames, or a .pc2")->required();
  app.add_option("--rest", rest, "the OBJ giving a point cache's triangles");
  app.add_option("--out", out, "output folder")->required();
  app.add_option("--first", first, "first source frame")->check(CLI::NonNegativeNumber);
  app.add_option("--stride", stride, "source frames per benchmark frame")->check(CLI::PositiveNumber);
  app.add_option("--count", count, "benchmark frames (default: as many as there are)");
  app.add_option("--seed", seed, "base random seed (frame k uses seed + k)");
  app.add_option("--iterations", iterations, "iterations of the first remeshing pass");
  app.add_option("--length-factor", length_factor, "target edge length / source mean edge length");
  CLI11_PARSE(app, argc, argv);

  try {
    const Source src = open_source(source_path, rest);
    const int available = (src.frames - 1 - first) / stride + 1;
    if (first >= src.frames) throw std::runtime_error("--first is past the last source frame");
    if (count < 0 || count > available) count = available;
    fs::create_directories(out / "raw");
    fs::create_directories(out / "truth");

    const sm::Positions V0 = src.positions(first);
    const double source_edge = sm::mean_edge_length(sm::TriMesh{V0, src.F});
    const double length = source_edge * length_factor;
    std::vector<Location> where;
    sm::TriMesh templ;
    std::ostringstream vcounts;
    for (int k = 0; k < count; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      const int s = first + k * stride;
      const sm::Positions V = k == 0 ? V0 : src.positions(s);
      const sm::TriMesh raw = remesh_frame(V, src.F, length, iterations, seed + unsigned(k));
      write_text(out / "raw" / frame_name(k), obj_text(raw.V, raw.F, nullptr));
      if (k == 0) {
        templ = raw;
        write_text(out / "template.obj", obj_text(raw.V, raw.F, nullptr));
        where = locate(raw.V, V, src.F);
        std::string csv = "vertex,triangle,b0,b1,b2,distance\n";
        char line[200];
        for (size_t i = 0; i < where.size(); ++i) {
          const Location& l = where[i];
          std::snprintf(line, sizeof line, "%zu,%d,%.17g,%.17g,%.17g,%.6g\n", i, l.triangle,
                        l.b[0], l.b[1], l.b[2], l.distance);
          csv += line;
        }
        write_text(out / "truth" / "locations.csv", csv);
      }
      const sm::Positions normals = sm::triangle_normals(sm::TriMesh{V, src.F});
      sm::Positions T(where.size(), 3), N(where.size(), 3);
      for (size_t i = 0; i < where.size(); ++i) {
        const Location& l = where[i];
        T.row(i).setZero();
        for (int c = 0; c < 3; ++c) T.row(i) += l.b[c] * V.row(src.F(l.triangle, c));
        N.row(i) = normals.row(l.triangle);
      }
      write_text(out / "truth" / frame_name(k), obj_text(T, templ.F, &N));
      vcounts << (k ? ", " : "") << raw.num_vertices();
      const double sec =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("frame %d (source %d): %d vertices, %d triangles, %.2f s\n", k, s,
                  raw.num_vertices(), raw.num_triangles(), sec);
      std::fflush(stdout);
    }
    double max_distance = 0;
    for (const Location& l : where) max_distance = std::max(max_distance, l.distance);
    std::ostringstream meta;
    meta.precision(10);
    meta << "{\n  \"source\": \"" << source_path.filename().string() << "\",\n"
         << "  \"source_frames\": {\"first\": " << first << ", \"stride\": " << stride
         << ", \"count\": " << count << "},\n"
         << "  \"seed\": " << seed << ",\n  \"target_edge_length\": " << length << ",\n"
         << "  \"source_mean_edge_length\": " << source_edge << ",\n"
         << "  \"template_mean_edge_length\": " << sm::mean_edge_length(templ) << ",\n"
         << "  \"template_max_distance_to_source\": " << max_distance << ",\n"
         << "  \"raw_vertices\": [" << vcounts.str() << "]\n}\n";
    write_text(out / "meta.json", meta.str());
    std::printf("template: %d vertices, mean edge %.6g (source %.6g), max distance to source %.3g\n",
                templ.num_vertices(), sm::mean_edge_length(templ), source_edge, max_distance);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_track_remesh: %s\n", e.what());
    return 1;
  }
  return 0;
}
