// The right-hand side of one mode, dx/dt = f(x, t), as a view
// (platform/function_ref.hpp): what the steppers that need nothing else of
// the system take, so that each of them is compiled once per state type,
// not once per system, at one indirect call per evaluation.
#pragma once

#include <impactlab/platform/function_ref.hpp>

namespace impactlab {

template <class State>
using StateRhs = FunctionRef<void(const State&, State&, double)>;

}  // namespace impactlab
