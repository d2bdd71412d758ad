#pragma once
/// The config keys of the distances' options (distance_options.hpp), the sequence job's
/// "measures" object (corresponding_triangles is the job's to set): one table line per member,
/// read by the JSON reader, `seqmassage config --reference`, the Python module and the
/// distances' own range check (core/options_table.hpp).
#include "core/options_table.hpp"
#include "geometry/distance_options.hpp"

namespace sm {

template <>
const Fields<DistanceOptions>& fields_of<DistanceOptions>();

}  // namespace sm
