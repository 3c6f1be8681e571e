// Which columns of events.csv (and fields of Python's events array) a run
// has: the core's, which every model fills (t, kind, wall, q, qdot_before,
// qdot_after, accumulation_error), and those only some models fill, as the
// scene's binding declares them (api/scene_system.hpp, event_columns). A
// model writes only its own: the bouncing ball has no friction work.
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace impactlab {

// The columns only some models fill, in events.csv's order (after
// qdot_after, before accumulation_error).
enum class EventColumn : std::size_t {
  normal_impulse,             // P_N (N s)
  tangential_velocity,        // γ_T at the event (m/s)
  normal_force,               // λ_N (N)
  friction_work,              // J, cumulative over contact phases
  instantaneous_residual,     // the pendulum's Model P (io/event_extension.hpp)
  sliding_residual,           // the pendulum's Model P
  tangential_velocity_after,  // γ_T just after an impact (the rigid model)
};
inline constexpr std::size_t event_column_count = 7;

std::string_view column_name(EventColumn column);

class EventColumns {
 public:
  // the core's columns only
  EventColumns() = default;
  EventColumns(std::initializer_list<EventColumn> columns);
  // every column (a writer that does not know the model)
  static EventColumns all();

  [[nodiscard]] bool has(EventColumn column) const {
    return present_[static_cast<std::size_t>(column)];
  }
  // every column present, the core's included, in the file's order
  [[nodiscard]] std::vector<std::string_view> names() const;
  // events.csv's header line (with its newline)
  [[nodiscard]] std::string header() const;

 private:
  std::array<bool, event_column_count> present_{};
};

}  // namespace impactlab
