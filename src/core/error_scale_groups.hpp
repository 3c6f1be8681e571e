// Which state components share one size when a step's error is measured
// against the state (integrate/taylor_stepper.hpp): the error allowed in a
// component is the tolerance times the largest size in its group.
//
// By default the mechanical state, the first tangent_dimension_of<S>
// components (core/has_jacobian.hpp), is one group, and each bookkeeping
// component after it (a friction work, the ball's spin angle) is a group of
// its own. A bookkeeping quantity grows without bound over a long run (the
// free ball's spin angle reaches 10⁴ rad in a few hundred periods); measured
// in one group with the motion, it would loosen the motion's tolerance by
// that factor, and events would move by far more than the tolerance.
//
// A system that needs another grouping declares it as a static member
// `error_scale_groups`: one group index per state component, the
// mechanical state's group 0 (the witnesses are measured against it). The
// variational equations (analysis/variational.hpp) do: the base's groups,
// then the fundamental matrix as one group.
#pragma once

#include <array>
#include <cstddef>
#include <tuple>

#include <impactlab/core/has_jacobian.hpp>

namespace impactlab {

template <class S>
using ErrorScaleGroupsOf = std::array<std::size_t, std::tuple_size_v<typename S::State>>;

template <class S>
constexpr ErrorScaleGroupsOf<S> error_scale_groups_of() {
  if constexpr (requires { S::error_scale_groups; }) {
    return S::error_scale_groups;
  } else {
    ErrorScaleGroupsOf<S> groups{};
    constexpr std::size_t mechanical = tangent_dimension_of<S>;
    for (std::size_t i = 0; i < groups.size(); ++i)
      groups[i] = i < mechanical ? 0 : i - mechanical + 1;
    return groups;
  }
}

// the number of groups: one more than the largest index
template <class S>
constexpr std::size_t error_scale_group_count() {
  std::size_t largest = 0;
  for (std::size_t group : error_scale_groups_of<S>()) largest = group > largest ? group : largest;
  return largest + 1;
}

}  // namespace impactlab
