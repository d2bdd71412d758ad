#pragma once
/// The config keys of the measures' options (measure_options.hpp), the single-mesh jobs'
/// "measures" object: one table line per member, read by the JSON reader, `seqmassage config
/// --reference` and the Python measure_keys() (core/options_table.hpp).
#include "core/options_table.hpp"
#include "geometry/measure_options.hpp"

namespace sm {

template <>
const Fields<MeasureOptions>& fields_of<MeasureOptions>();

}  // namespace sm
