#include "pipeline/report/report_json.hpp"

#include <cmath>

#include "io/csv.hpp"

namespace sm {
using json = nlohmann::json;

json json_number(double x) {
  return std::isfinite(x) ? json(x) : json(format_number(x));
}

json distance_json(const DistanceStats& d) {
  return {{"max", json_number(d.max)},
          {"mean", json_number(d.mean)},
          {"rms", json_number(d.rms)},
          {"max_rel", json_number(d.max_rel)},
          {"mean_rel", json_number(d.mean_rel)},
          {"rms_rel", json_number(d.rms_rel)},
          {"samples", d.samples}};
}

}  // namespace sm
