#include "pipeline/sequence/sequence_options.hpp"

#include "io/options_json.hpp"

namespace sm {

DistanceOptions default_sequence_measures() {
  DistanceOptions o;  // the sampling's defaults, but adaptive
  o.adaptive = true;
  o.spacing = 0.125;
  o.corresponding_triangles = true;
  return o;
}

nlohmann::json to_json(const SequenceJobOptions& options) {
  return write_options(options);
}

}  // namespace sm
