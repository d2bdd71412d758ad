#include "mesh/primitives.hpp"

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace sm {
namespace {

TriMesh from_vectors(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& f) {
  TriMesh m;
  m.V.resize(static_cast<int>(v.size()), 3);
  for (size_t i = 0; i < v.size(); ++i) m.V.row(static_cast<int>(i)) = v[i].transpose();
  m.F.resize(static_cast<int>(f.size()), 3);
  for (size_t i = 0; i < f.size(); ++i)
    for (int k = 0; k < 3; ++k) m.F(static_cast<int>(i), k) = f[i][k];
  return m;
}

// Splits the quad (a, b, c, d), counter-clockwise, along a diagonal chosen by `flip`.
void quad(std::vector<std::array<int, 3>>& f, int a, int b, int c, int d, bool flip) {
  if (flip) {
    f.push_back({a, b, d});
    f.push_back({b, c, d});
  } else {
    f.push_back({a, b, c});
    f.push_back({a, c, d});
  }
}

}  // namespace

TriMesh make_grid(int nx, int ny, double sx, double sy) {
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> f;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) v.emplace_back(sx * i / nx, sy * j / ny, 0.0);
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      quad(f, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 1);
  return from_vectors(v, f);
}

TriMesh make_icosphere(int subdivisions, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      const int id = static_cast<int>(v.size()) - 1;
      mid.emplace(key, id);
      return id;
    };
    std::vector<std::array<int, 3>> g;
    g.reserve(f.size() * 4);
    for (const auto& tri : f) {
      const int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]),
                c = midpoint(tri[2], tri[0]);
      g.push_back({tri[0], a, c});
      g.push_back({tri[1], b, a});
      g.push_back({tri[2], c, b});
      g.push_back({a, b, c});
    }
    f.swap(g);
  }
  for (auto& p : v) p *= radius;
  return from_vectors(v, f);
}

TriMesh make_torus(int nu, int nv, double R, double r) {
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> f;
  const double two_pi = 2.0 * M_PI;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double u = two_pi * i / nu, w = two_pi * j / nv;
      v.emplace_back((R + r * std::cos(w)) * std::cos(u), (R + r * std::cos(w)) * std::sin(u),
                     r * std::sin(w));
    }
  auto id = [&](int i, int j) { return (j % nv) * nu + (i % nu); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      quad(f, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 1);
  return from_vectors(v, f);
}

TriMesh make_cylinder(int nu, int nv, double radius, double height) {
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> f;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double u = 2.0 * M_PI * i / nu;
      v.emplace_back(radius * std::cos(u), radius * std::sin(u), height * j / nv);
    }
  auto id = [&](int i, int j) { return j * nu + (i % nu); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      quad(f, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 1);
  return from_vectors(v, f);
}

TriMesh make_box(int n, double sx, double sy, double sz) {
  // Vertices live on the integer lattice {0..n}^3 restricted to the surface, so the six faces
  // share their edge and corner vertices exactly.
  std::map<std::array<int, 3>, int> index;
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> f;
  auto vid = [&](std::array<int, 3> g) {
    auto it = index.find(g);
    if (it != index.end()) return it->second;
    v.emplace_back(sx * g[0] / n, sy * g[1] / n, sz * g[2] / n);
    const int id = static_cast<int>(v.size()) - 1;
    index.emplace(g, id);
    return id;
  };
  // For each axis and side, two in-plane axes (u, w) ordered so that u × w points outward.
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      int u = (axis + 1) % 3, w = (axis + 2) % 3;
      if (side == 0) std::swap(u, w);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          auto g = [&](int a, int b) {
            std::array<int, 3> p{};
            p[axis] = side * n;
            p[u] = a;
            p[w] = b;
            return vid(p);
          };
          quad(f, g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1), (i + j) % 2 == 1);
        }
    }
  return from_vectors(v, f);
}

}  // namespace sm
