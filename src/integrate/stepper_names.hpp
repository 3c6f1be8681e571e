// The integrator.method names, without the steppers themselves (for scene
// validation and front ends; integrate/stepper_dispatch.hpp builds them).
#pragma once

#include <array>
#include <string_view>

namespace impactlab {

// every integrator.method value, in the order the docs list them
inline constexpr std::array<std::string_view, 6> stepper_names = {
    "dopri5", "rkf78", "bulirsch_stoer", "rk8pd", "taylor", "exact"};

inline bool is_stepper_name(std::string_view name) {
  for (auto known : stepper_names)
    if (known == name) return true;
  return false;
}

}  // namespace impactlab
