#pragma once
/// The plan of a sequence job: everything a run needs, checked (plan_sequence_job builds it
/// without writing anything). A low header, like frame_summary.hpp: the outputs, the frame
/// processor and the reports include it; it names the outputs by forward declaration only.
#include <memory>
#include <string>
#include <vector>

#include "geometry/distance_meter.hpp"
#include "massage/massage.hpp"
#include "mesh/mesh.hpp"
#include "pipeline/frame_source.hpp"
#include "pipeline/sequence_options.hpp"

namespace sm {

class FrameOutput;

struct SequencePlan {
  SequenceJobOptions config;
  std::shared_ptr<const FrameSource> source;  ///< every input frame, in order
  /// The per-frame outputs the config enables, in registry order (make_frame_outputs). Their
  /// encode and plan methods are const; start() is called once per run, before any frame.
  std::vector<std::shared_ptr<FrameOutput>> outputs;
  std::vector<int> selected;    ///< indices of the job's selected frames, in order
  std::vector<int> run_frames;  ///< the frames this run processes: `selected`, or its shard of them
  int template_frame = -1;      ///< index of the template frame, -1 for a mesh
  std::string template_source;  ///< e.g. "frame 0 (frame_0000.obj)"
  TriMesh templ;                ///< the original template: weights and shear
  std::shared_ptr<const Massager> massager;  ///< built once from the template
  /// The distances between each frame and its output (sampling layout and scratch, built once).
  std::shared_ptr<const DistanceMeter> distance_meter;
  int threads = 1;            ///< resolved worker threads
  int frames_in_flight = 2;   ///< resolved pipeline tokens
  std::string config_hash;    ///< frame_config_hash(config), kept in every frame record
  std::string template_hash;  ///< template_hash(templ)
  std::vector<std::string> warnings;
};

}  // namespace sm
