#include "massage/shape_target.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>

namespace sm {
namespace {

// Area-weighted vertex normals (unnormalized: the sum of the cross products of the triangles
// around each vertex), gathered per vertex in the topology's order, so the bits do not depend on
// the thread count.
Positions area_normals(const Positions& V, const Triangles& F, const Topology& topo) {
  const int m = static_cast<int>(F.rows()), n = static_cast<int>(V.rows());
  Positions face(m, 3);
  tbb::parallel_for(tbb::blocked_range<int>(0, m, 4096), [&](const tbb::blocked_range<int>& r) {
    for (int t = r.begin(); t != r.end(); ++t) {
      const Vec3 a = V.row(F(t, 0)).transpose();
      face.row(t) =
          (V.row(F(t, 1)).transpose() - a).cross(V.row(F(t, 2)).transpose() - a).transpose();
    }
  });
  Positions out(n, 3);
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 4096), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) {
      Vec3 s = Vec3::Zero();
      for (int p = topo.vertex_triangles.begin(i); p < topo.vertex_triangles.end(i); ++p)
        s += face.row(topo.vertex_triangles.data[p]).transpose();
      out.row(i) = s.transpose();
    }
  });
  return out;
}

// The unit normal of an area-weighted sum, or zero when it has (relatively) no length.
Vec3 unit_or_zero(const Vec3& s, double scale2) {
  const double l2 = s.squaredNorm();
  return l2 > 1e-24 * scale2 && std::isfinite(l2) ? Vec3(s / std::sqrt(l2)) : Vec3(Vec3::Zero());
}

// Squared length scale of vertex i's ring (sum of λ-weighted squared edges; the cross products
// summed into a normal are of that order).
double ring_scale2(const Positions& V, const SparseMatrixR& lambda, int i) {
  double s = 0.0;
  for (SparseMatrixR::InnerIterator it(lambda, i); it; ++it)
    s += (V.row(it.col()) - V.row(i)).squaredNorm();
  return s * s;
}

// A unit vector perpendicular to unit n, chosen deterministically.
Vec3 any_tangent(const Vec3& n) {
  const Vec3 axis = std::abs(n.x()) <= std::abs(n.y()) && std::abs(n.x()) <= std::abs(n.z())
                        ? Vec3::UnitX()
                    : std::abs(n.y()) <= std::abs(n.z()) ? Vec3::UnitY()
                                                         : Vec3::UnitZ();
  return n.cross(axis).normalized();
}

// The closed classes of the Markov chain Λ: strongly connected components of the graph with an
// edge i -> j wherever λ_ij > 0 that no edge leaves (iterative Tarjan). Vertices with an empty
// row (no shape) are left out.
std::vector<std::vector<int>> closed_classes(const SparseMatrixR& L) {
  const int n = static_cast<int>(L.rows());
  const int* outer = L.outerIndexPtr();
  const int* inner = L.innerIndexPtr();
  const double* val = L.valuePtr();
  std::vector<int> index(n, -1), low(n, 0), component(n, -1), stack, call;
  std::vector<int> next(n, 0);
  std::vector<unsigned char> on_stack(n, 0);
  int counter = 0, components = 0;
  std::vector<std::vector<int>> members;
  for (int root = 0; root < n; ++root) {
    if (index[root] >= 0) continue;
    call.push_back(root);
    index[root] = low[root] = counter++;
    next[root] = outer[root];
    stack.push_back(root);
    on_stack[root] = 1;
    while (!call.empty()) {
      const int v = call.back();
      bool descended = false;
      while (next[v] < outer[v + 1]) {
        const int p = next[v]++;
        const int w = inner[p];
        if (!(val[p] > 0.0) || w == v) continue;
        if (index[w] < 0) {
          index[w] = low[w] = counter++;
          next[w] = outer[w];
          stack.push_back(w);
          on_stack[w] = 1;
          call.push_back(w);
          descended = true;
          break;
        }
        if (on_stack[w]) low[v] = std::min(low[v], index[w]);
      }
      if (descended) continue;
      call.pop_back();
      if (!call.empty()) low[call.back()] = std::min(low[call.back()], low[v]);
      if (low[v] == index[v]) {
        members.emplace_back();
        int w;
        do {
          w = stack.back();
          stack.pop_back();
          on_stack[w] = 0;
          component[w] = components;
          members.back().push_back(w);
        } while (w != v);
        ++components;
      }
    }
  }
  std::vector<unsigned char> closed(components, 1);
  for (int v = 0; v < n; ++v) {
    if (outer[v + 1] == outer[v]) closed[component[v]] = 0;  // no shape
    for (int p = outer[v]; p < outer[v + 1]; ++p)
      if (val[p] > 0.0 && component[inner[p]] != component[v]) closed[component[v]] = 0;
  }
  std::vector<std::vector<int>> out;
  for (int c = 0; c < components; ++c)
    if (closed[c] && members[c].size() >= 2) {
      std::sort(members[c].begin(), members[c].end());
      out.push_back(std::move(members[c]));
    }
  return out;
}

// The stationary distribution π of Λ restricted to a closed class C (πᵀ Λ_CC = πᵀ, Σ π = 1): the
// left null vector of the class's block of A = I − Λ.
Eigen::VectorXd stationary(const SparseMatrixR& L, const std::vector<int>& C) {
  const int size = static_cast<int>(C.size());
  auto local = [&](int v) {
    return static_cast<int>(std::lower_bound(C.begin(), C.end(), v) - C.begin());
  };
  // (I − Λ_CC)ᵀ π = 0 with its last equation replaced by π_last = 1 (the null space is
  // one-dimensional on a closed class, so the system is regular; a sparse row keeps the fill-in
  // of the factorization low), then normalized.
  std::vector<Eigen::Triplet<double>> trip;
  for (int a = 0; a < size; ++a) {
    const int i = C[a];
    if (a != size - 1) trip.emplace_back(a, a, 1.0);
    for (SparseMatrixR::InnerIterator it(L, i); it; ++it) {
      const int b = local(static_cast<int>(it.col()));
      if (b != size - 1 && it.value() != 0.0) trip.emplace_back(b, a, -it.value());
    }
  }
  trip.emplace_back(size - 1, size - 1, 1.0);
  Eigen::SparseMatrix<double> M(size, size);
  M.setFromTriplets(trip.begin(), trip.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(M);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size);
  rhs[size - 1] = 1.0;
  Eigen::VectorXd pi = lu.info() == Eigen::Success ? Eigen::VectorXd(lu.solve(rhs))
                                                   : Eigen::VectorXd::Constant(size, 1.0 / size);
  if (!pi.allFinite() || !(pi.sum() > 0.0)) pi.setConstant(1.0);
  return pi / pi.sum();
}

}  // namespace

ShapeTarget::ShapeTarget(const TriMesh& templ, const SparseMatrixR& lambda,
                         const Topology& topology) {
  const int n = templ.num_vertices();
  const int* outer = lambda.outerIndexPtr();  // Λ is compressed (compute_weights)
  const int* inner = lambda.innerIndexPtr();
  const double* value = lambda.valuePtr();
  verts_.resize(n);
  edges_.assign(2 * static_cast<size_t>(lambda.nonZeros()), 0.0);
  const Positions normals = area_normals(templ.V, templ.F, topology);
  for (int i = 0; i < n; ++i) {
    Vertex& v = verts_[i];
    const Vec3 nrm = unit_or_zero(normals.row(i).transpose(), ring_scale2(templ.V, lambda, i));
    const Vec3 u = nrm.squaredNorm() > 0.0 ? any_tangent(nrm) : Vec3(Vec3::Zero());
    const Vec3 w = nrm.cross(u);
    Vec3 lap = Vec3::Zero();  // (A T)_i = −Σ_j λ_ij (t_j − t_i)
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const Vec3 e = templ.vertex(inner[k]) - templ.vertex(i);
      lap -= value[k] * e;
      edges_[2 * static_cast<size_t>(k)] = value[k] * e.dot(u);
      edges_[2 * static_cast<size_t>(k) + 1] = value[k] * e.dot(w);
    }
    v.has_normal = nrm.squaredNorm() > 0.0;
    v.tangent[0] = lap.dot(u);
    v.tangent[1] = lap.dot(w);
    v.normal_part = lap.dot(nrm);
  }
  for (std::vector<int>& C : closed_classes(lambda)) {
    if (static_cast<int>(C.size()) > kMaxProjectedClass) continue;
    const Eigen::VectorXd pi = stationary(lambda, C);
    classes_.push_back({std::move(C), std::vector<double>(pi.data(), pi.data() + pi.size())});
  }
}

int ShapeTarget::evaluate(const Positions& start, const Triangles& F, const SparseMatrixR& lambda,
                          const Topology& topology, Positions& delta) const {
  const int n = static_cast<int>(start.rows());
  const Positions normals = area_normals(start, F, topology);
  const int* outer = lambda.outerIndexPtr();
  const int* inner = lambda.innerIndexPtr();
  delta.resize(n, 3);
  std::vector<unsigned char> fallback(n, 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 2048), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) {
      const Vertex& v = verts_[i];
      const Vec3 ns = unit_or_zero(normals.row(i).transpose(), ring_scale2(start, lambda, i));
      if (!v.has_normal) {
        delta.row(i).setZero();
        fallback[i] = outer[i + 1] > outer[i];
        continue;
      }
      if (ns.squaredNorm() == 0.0) {
        delta.row(i).setZero();
        fallback[i] = 1;
        continue;
      }
      // S's tangent frame (any: the twist below absorbs the choice of u).
      const Vec3 u = any_tangent(ns), w = ns.cross(u);
      // The twist: the closest rotation to Σ_j q_j p_jᵀ, q_j = S's edge in (u, w), p_j = T's
      // λ-weighted edge in T's frame: cos ∝ Σ q·p, sin ∝ Σ q × p.
      const Vec3 si = start.row(i).transpose();
      double a = 0.0, b = 0.0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) {
        const Vec3 e = start.row(inner[k]).transpose() - si;
        const double qx = e.dot(u), qy = e.dot(w);
        const double px = edges_[2 * static_cast<size_t>(k)];
        const double py = edges_[2 * static_cast<size_t>(k) + 1];
        a += qx * px + qy * py;
        b += qy * px - qx * py;
      }
      const double len = std::hypot(a, b);
      const double cs = len > 0.0 ? a / len : 1.0, sn = len > 0.0 ? b / len : 0.0;
      const double x = cs * v.tangent[0] - sn * v.tangent[1];
      const double y = sn * v.tangent[0] + cs * v.tangent[1];
      delta.row(i) = (x * u + y * w + v.normal_part * ns).transpose();
    }
  });
  for (const Class& cls : classes_) {
    Vec3 mean = Vec3::Zero();
    for (size_t a = 0; a < cls.vertices.size(); ++a)
      mean += cls.pi[a] * delta.row(cls.vertices[a]).transpose();
    for (int v : cls.vertices) delta.row(v) -= mean.transpose();
  }
  int count = 0;
  for (unsigned char f : fallback) count += f;
  return count;
}

}  // namespace sm
