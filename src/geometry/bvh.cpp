#include "geometry/bvh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "geometry/closest_point.hpp"
#include "geometry/float_bounds.hpp"
#include "core/errors.hpp"

namespace sm {
namespace {

constexpr int kLeafSize = 4;
// A leaf reference packs the first entry and the count (< 8) into a negative int.
constexpr int kMaxTriangles = 1 << 28;
// The median split halves every range, so the tree depth is at most log2(m) + 1 < 30 and a
// traversal pushes at most one entry per level.
constexpr int kStackSize = 64;

int leaf_ref(int first, int count) {
  return ~((first << 3) | count);
}
int leaf_first(int ref) {
  return (~ref) >> 3;
}
int leaf_count(int ref) {
  return (~ref) & 7;
}

constexpr float kFloatInf = std::numeric_limits<float>::infinity();

}  // namespace

TriangleBvh::TriangleBvh(const TriMesh& mesh) : V_(mesh.V), F_(mesh.F) {
  validate_mesh(mesh, "TriangleBvh");
  const int m = static_cast<int>(F_.rows());
  if (m == 0) return;
  if (m >= kMaxTriangles) {
    std::ostringstream msg;
    msg << "TriangleBvh: " << m << " triangles, at most " << kMaxTriangles - 1 << " supported";
    throw InputError(msg.str());
  }
  std::vector<Vec3> centroids(m);
  for (int t = 0; t < m; ++t)
    centroids[t] = (V_.row(F_(t, 0)) + V_.row(F_(t, 1)) + V_.row(F_(t, 2))).transpose() / 3.0;
  order_.resize(m);
  std::iota(order_.begin(), order_.end(), 0);
  // Leaves hold 2 to 4 triangles: fewer than m / 2 inner nodes.
  nodes_.reserve(m / 2 + 1);
  nodes_.emplace_back();
  if (m <= kLeafSize) {
    nodes_[0].child[0] = leaf_ref(0, m);
    nodes_[0].child[1] = leaf_ref(0, 0);
  } else {
    build(0, 0, m, centroids);
  }
  corners_.resize(static_cast<size_t>(m) * 3);
  refit(V_);
}

void TriangleBvh::build(int node, int first, int count, std::vector<Vec3>& centroids) {
  // Object median along the longest axis of the centroids' bounding box. Ties are broken by
  // triangle id so the tree does not depend on the standard library's partitioning.
  Eigen::AlignedBox3d cbox;
  for (int i = first; i < first + count; ++i) cbox.extend(centroids[order_[i]]);
  int axis = 0;
  cbox.sizes().maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half,
                   order_.begin() + first + count, [&](int s, int t) {
                     const double cs = centroids[s][axis], ct = centroids[t][axis];
                     return cs < ct || (cs == ct && s < t);
                   });
  const int range_first[2] = {first, first + half};
  const int range_count[2] = {half, count - half};
  for (int k = 0; k < 2; ++k) {
    if (range_count[k] <= kLeafSize) {
      nodes_[node].child[k] = leaf_ref(range_first[k], range_count[k]);
      continue;
    }
    const int inner = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    nodes_[node].child[k] = inner;
    build(inner, range_first[k], range_count[k], centroids);
  }
}

void TriangleBvh::refit(const Positions& V) {
  if (V.rows() != V_.rows()) {
    std::ostringstream msg;
    msg << "TriangleBvh::refit: " << V.rows() << " positions for a mesh of " << V_.rows()
        << " vertices";
    throw InputError(msg.str());
  }
  if (&V != &V_) V_ = V;
  // Children are created after their parent, so a reverse sweep visits them first.
  for (int i = static_cast<int>(nodes_.size()) - 1; i >= 0; --i) {
    Node& node = nodes_[i];
    for (int k = 0; k < 2; ++k) {
      const int ref = node.child[k];
      if (ref >= 0) {
        const Node& c = nodes_[ref];
        for (int a = 0; a < 3; ++a) {
          node.lo[k][a] = std::min(c.lo[0][a], c.lo[1][a]);
          node.hi[k][a] = std::max(c.hi[0][a], c.hi[1][a]);
        }
        continue;
      }
      if (leaf_count(ref) == 0) {  // the empty child of a small mesh's root: never visited
        for (int a = 0; a < 3; ++a) {
          node.lo[k][a] = kFloatInf;
          node.hi[k][a] = -kFloatInf;
        }
        continue;
      }
      Eigen::AlignedBox3d box;
      for (int s = leaf_first(ref); s < leaf_first(ref) + leaf_count(ref); ++s) {
        const int t = order_[s];
        for (int j = 0; j < 3; ++j) {
          corners_[3 * s + j] = V_.row(F_(t, j)).transpose();
          box.extend(corners_[3 * s + j]);
        }
      }
      for (int a = 0; a < 3; ++a) {
        node.lo[k][a] = float_at_most(box.min()[a]);
        node.hi[k][a] = float_at_least(box.max()[a]);
      }
    }
  }
}

SurfacePoint TriangleBvh::closest(const Vec3& p, double max_dist2) const {
  SurfacePoint result;
  if (nodes_.empty()) return result;
  double best = max_dist2;
  int best_slot = -1;
  TrianglePoint best_tp{};
  int stack_ref[kStackSize];
  double stack_d2[kStackSize];
  int top = 0;
  int ref = 0;
  for (;;) {
    if (ref < 0) {
      const int end = leaf_first(ref) + leaf_count(ref);
      for (int s = leaf_first(ref); s < end; ++s) {
        const TrianglePoint tp =
            closest_point_on_triangle(p, corners_[3 * s], corners_[3 * s + 1], corners_[3 * s + 2]);
        if (tp.dist2 < best) {
          best = tp.dist2;
          best_slot = s;
          best_tp = tp;
        }
      }
    } else {
      // Both child boxes sit in this node; visit the nearer child first, park the other.
      const Node& node = nodes_[ref];
      double d2[2];
      for (int k = 0; k < 2; ++k) {
        double sum = 0.0;
        for (int a = 0; a < 3; ++a) {
          const double e = std::max(std::max(static_cast<double>(node.lo[k][a]) - p[a],
                                             p[a] - static_cast<double>(node.hi[k][a])),
                                    0.0);
          sum += e * e;
        }
        d2[k] = sum;
      }
      const int near = d2[1] < d2[0] ? 1 : 0;
      if (d2[near] < best) {
        if (d2[1 - near] < best) {
          stack_ref[top] = node.child[1 - near];
          stack_d2[top] = d2[1 - near];
          ++top;
        }
        ref = node.child[near];
        continue;
      }
    }
    // Pop the next subtree that can still hold something closer than the best so far.
    for (;;) {
      if (top == 0) {
        if (best_slot >= 0) {
          result.triangle = order_[best_slot];
          result.bary = best_tp.bary;
          result.point = best_tp.point;
          result.dist2 = best_tp.dist2;
        }
        return result;
      }
      --top;
      if (stack_d2[top] < best) break;
    }
    ref = stack_ref[top];
  }
}

}  // namespace sm
