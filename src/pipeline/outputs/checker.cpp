#include "pipeline/outputs/checker.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace sm {

std::optional<CornerUv> input_uv(const ObjFile& obj, const Triangles& F) {
  if (!obj.has_texcoords() || obj.mesh.F.rows() != F.rows() || obj.mesh.F != F) return std::nullopt;
  CornerUv out;
  out.uv = obj.texcoords;
  out.faces.resize(F.rows(), 3);
  out.source = "input";
  Eigen::Index t = 0;
  for (int f = 0; f < obj.num_faces(); ++f) {
    const int c0 = obj.face_offsets[size_t(f)];
    for (int c1 = c0 + 1; c1 + 1 < obj.face_offsets[size_t(f) + 1]; ++c1) {
      if (t >= F.rows()) return std::nullopt;
      const int corners[3] = {c0, c1, c1 + 1};
      for (int k = 0; k < 3; ++k) {
        const int vt = obj.corners[size_t(corners[k])].vt;
        if (vt < 0) return std::nullopt;
        out.faces(t, k) = vt;
      }
      ++t;
    }
  }
  if (t != F.rows()) return std::nullopt;
  return out;
}

CornerUv chart_uv(const TriMesh& templ, double period) {
  // (u axis, v axis) per chart +x, -x, +y, -y, +z, -z: u × v is the chart's normal.
  static const int kAxes[6][2] = {{1, 2}, {2, 1}, {2, 0}, {0, 2}, {0, 1}, {1, 0}};
  const Positions normals = triangle_normals(templ);
  const Eigen::RowVector3d low = templ.V.colwise().minCoeff();
  CornerUv out;
  out.faces.resize(templ.F.rows(), 3);
  out.source = "charts";
  std::map<std::pair<int, int>, int> index;  // (vertex, chart) -> uv row
  std::vector<std::array<double, 2>> uv;
  for (Eigen::Index t = 0; t < templ.F.rows(); ++t) {
    const Eigen::RowVector3d n = normals.row(t);
    int axis = 2;
    if (n.allFinite() && n.squaredNorm() > 0.0) n.cwiseAbs().maxCoeff(&axis);
    const int chart = 2 * axis + (n.allFinite() && n[axis] < 0.0 ? 1 : 0);
    for (int k = 0; k < 3; ++k) {
      const int v = templ.F(t, k);
      const auto [it, added] = index.emplace(std::make_pair(v, chart), int(uv.size()));
      if (added) {
        const Eigen::RowVector3d p = templ.V.row(v) - low;
        uv.push_back({p[kAxes[chart][0]] / period, p[kAxes[chart][1]] / period});
      }
      out.faces(t, k) = it->second;
    }
  }
  out.uv.resize(Eigen::Index(uv.size()), 2);
  for (size_t i = 0; i < uv.size(); ++i) out.uv.row(Eigen::Index(i)) << uv[i][0], uv[i][1];
  return out;
}

CornerUv template_uv(const TriMesh& templ, const ObjFile* obj,
                     const CheckerOutputOptions& options) {
  if (options.uv == CheckerUvSource::Auto && obj)
    if (std::optional<CornerUv> own = input_uv(*obj, templ.F)) return std::move(*own);
  double period = options.cells * options.cell_size * mean_edge_length(templ);
  if (!(period > 0.0) || !std::isfinite(period)) period = 1.0;
  return chart_uv(templ, period);
}

Image8 checker_texture(int cells) {
  cells = std::max(1, cells);
  const int square = std::max(8, 256 / cells);
  const int size = cells * square;
  Image8 image{size, size, 3, std::vector<uint8_t>(size_t(size) * size_t(size) * 3)};
  const uint8_t light[3] = {235, 235, 235}, dark[3] = {45, 50, 70};
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const uint8_t* c = ((x / square + y / square) % 2 == 0) ? light : dark;
      std::copy(c, c + 3, image.pixels.begin() + (ptrdiff_t(y) * size + x) * 3);
    }
  return image;
}

}  // namespace sm
