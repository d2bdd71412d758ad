#pragma once
/// Frames from a point cache (PC2 or MDD, io/point_cache.hpp) on a mesh: the cache gives every
/// frame's positions, the mesh (OBJ, PLY or OFF) the triangles, texture coordinates and materials
/// that every frame, and an OBJ output, shares.
#include <memory>

#include "pipeline/sequence/frame_source.hpp"
#include "pipeline/sequence/sequence_options.hpp"

namespace sm {

/// The source of `input`: reads and checks the cache's header (against the file's size) and the
/// mesh, and their vertex counts; frames are read one at a time, at their offset, when fetched.
/// Throws IoError when a file cannot be read, InputError for a malformed header or mesh, or
/// vertex counts that differ (naming both files and counts).
std::shared_ptr<const FrameSource> make_point_cache_source(const PointCacheInput& input);

}  // namespace sm
