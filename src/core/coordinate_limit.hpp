#pragma once
/// The coordinate range readers accept: finite values beyond it overflow the geometry.

namespace sm {

/// Largest coordinate magnitude a reader accepts (1e18): the geometry multiplies coordinates (areas,
/// squared distances in float BVH boxes, energies of fourth powers), so a finite but larger value
/// overflows them; readers refuse it as an input error naming the file, line or element and value.
inline constexpr double kMaxCoordinate = 1e18;

}  // namespace sm
