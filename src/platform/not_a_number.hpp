// A quiet NaN, the value of a number that is not available (written to the
// files as an empty or "nan" field).
#pragma once

#include <limits>

namespace impactlab {

inline constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

}  // namespace impactlab
