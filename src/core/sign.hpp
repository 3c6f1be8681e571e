// The sign of a number (−1, 0 or +1), as a free function so that a
// right-hand side written over a number type calls it unqualified and a
// series type supplies its own (integrate/taylor_series.hpp).
#pragma once

namespace impactlab {

inline double sign(double v) { return v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : 0.0; }

}  // namespace impactlab
