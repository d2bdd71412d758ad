#pragma once
/// The config keys of the optimizer's options (massage_options.hpp), the "massage" object: one
/// table line per member with its JSON name, its range or names and its documentation, which the
/// JSON reader, `seqmassage config --reference`, the Python massage_keys() and the Massager's own
/// range check read (core/options_table.hpp).
#include "core/options_table.hpp"
#include "massage/massage_options.hpp"

namespace sm {

inline constexpr EnumName<DistanceTerm> kDistanceTermNames[] = {{"point", DistanceTerm::Point},
                                                                {"plane", DistanceTerm::Plane}};
inline constexpr EnumName<SolverKind> kSolverKindNames[] = {{"iterative", SolverKind::Iterative},
                                                            {"direct", SolverKind::Direct}};
inline constexpr EnumName<ClosestPointMode> kClosestPointModeNames[] = {
    {"local", ClosestPointMode::Local}, {"exact", ClosestPointMode::Exact}};

/// The "massage" table: the paper's method, then the numerics, then the extensions.
template <>
const Fields<MassageOptions>& fields_of<MassageOptions>();

}  // namespace sm
