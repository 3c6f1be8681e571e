// The names of a system's state components, in its order, for the files that
// write a whole state (periodic.json's `state`): a system declares them with
// state_names(); the names are those of the scene's keys where one exists
// (initial.theta: "theta"), plain words otherwise ("friction_work").
#pragma once

#include <concepts>
#include <string>
#include <string_view>
#include <vector>

namespace impactlab {

template <class System>
concept HasStateNames = requires(const System& system) {
  { system.state_names() } -> std::convertible_to<std::vector<std::string_view>>;
};

// The names as text; empty for a system that does not declare them.
template <class System>
std::vector<std::string> state_names_of(const System& system) {
  if constexpr (HasStateNames<System>) {
    const std::vector<std::string_view> names = system.state_names();
    return {names.begin(), names.end()};
  } else {
    return {};
  }
}

}  // namespace impactlab
