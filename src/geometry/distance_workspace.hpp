#pragma once
/// Memory that one_sided_distance reuses from call to call (its triangle grid, the distances of
/// the adaptive samples), and a pool of such workspaces for concurrent callers, so that the
/// frames of a sequence do not allocate (and page-fault) megabytes anew for every distance.
#include <memory>
#include <mutex>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/triangle_grid.hpp"
#include "geometry/triangle_planes.hpp"

namespace sm {

/// Scratch of one call of one_sided_distance at a time; its contents mean nothing in between.
struct DistanceWorkspace {
  TriangleGrid grid;
  std::vector<double> vertex_distance, centroid_distance, triangle_max;
  std::vector<int> refine;
  std::vector<long> count;
  /// Not used by one_sided_distance: room for the caller's B when that is a moved copy (the
  /// sequence job's output frame: the input's BVH refitted, its projection frames), kept for the
  /// same reason (copy-assigning a BVH of the same size reuses these arrays).
  TriangleBvh bvh;
  TrianglePlanes planes;
};

/// Hands out workspaces that no other holder uses, and keeps them when they are given back:
/// as many are ever made as were held at once. Thread-safe.
class DistanceWorkspaces {
 public:
  /// A workspace for the lifetime of the lease; back to the pool when the lease ends.
  class Lease {
   public:
    Lease(DistanceWorkspaces& pool, std::unique_ptr<DistanceWorkspace> work)
        : pool_(&pool), work_(std::move(work)) {}
    Lease(Lease&&) = default;
    Lease& operator=(Lease&&) = delete;
    ~Lease() {
      if (work_) pool_->give_back(std::move(work_));
    }
    DistanceWorkspace* get() const { return work_.get(); }

   private:
    DistanceWorkspaces* pool_;
    std::unique_ptr<DistanceWorkspace> work_;
  };

  Lease acquire() {
    std::unique_ptr<DistanceWorkspace> work;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!free_.empty()) {
        work = std::move(free_.back());
        free_.pop_back();
      }
    }
    if (!work) work = std::make_unique<DistanceWorkspace>();
    return Lease(*this, std::move(work));
  }

 private:
  void give_back(std::unique_ptr<DistanceWorkspace> work) {
    const std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(work));
  }

  std::mutex mutex_;
  std::vector<std::unique_ptr<DistanceWorkspace>> free_;
};

}  // namespace sm
