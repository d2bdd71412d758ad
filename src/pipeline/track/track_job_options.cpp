#include "pipeline/track/track_job_options.hpp"

#include "io/options_json.hpp"

namespace sm {

nlohmann::json to_json(const TrackJobOptions& options) {
  return write_options(options);
}

SequenceJobOptions output_job_options(const TrackJobOptions& options) {
  SequenceJobOptions s;
  s.input.frames = options.input.frames;
  s.input.range = options.input.range;
  s.templ.frame = options.templ.frame;
  s.templ.mesh = options.templ.mesh;
  s.output = options.output;
  s.massage = options.massage;
  s.massage.iterations = options.track.refine_iterations;
  s.threads = options.threads;
  s.shard = options.shard;
  s.config_file = options.config_file;
  return s;
}

}  // namespace sm
