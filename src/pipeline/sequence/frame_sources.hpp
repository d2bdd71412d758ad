#pragma once
/// The frame sources of the config's input: a folder of OBJ files, the generated synthetic
/// sequence and a glTF animation (here), PC2 and MDD point caches (point_cache_source.hpp), behind
/// the FrameSource interface (frame_source.hpp), and the factory that picks one.
#include <memory>

#include "io/gltf/gltf_load.hpp"
#include "pipeline/sequence/frame_source.hpp"
#include "pipeline/sequence/sequence_options.hpp"

namespace sm {

/// The source of the config's input ("frames", "synthetic", "gltf", "pc2" or "mdd"). A glTF file is loaded,
/// welded and checked here; other sources list or generate nothing yet. Throws like the loaders:
/// IoError, InputError naming the file and element, ConfigError for invalid values. For a glTF
/// input, `gltf` (if given) receives the loaded asset, which an output that rebuilds it (the
/// GLB) is built with.
std::shared_ptr<const FrameSource> make_frame_source(
    const SequenceJobOptions& config, std::shared_ptr<const GltfSequence>* gltf = nullptr);

}  // namespace sm
