#pragma once
/// JSON values shared by report.json, the frame records and the single-mesh report: numbers that
/// may be infinite or NaN, and distance statistics.
#include <nlohmann/json.hpp>

#include "geometry/distance.hpp"

namespace sm {

/// A finite number as a JSON number (shortest round trip); infinity and NaN, which JSON lacks, as
/// the strings CSV uses ("inf", "-inf", "nan").
nlohmann::json json_number(double x);

/// Distance statistics as {max, mean, rms, max_rel, mean_rel, rms_rel, samples} (json_number).
nlohmann::json distance_json(const DistanceStats& d);

}  // namespace sm
