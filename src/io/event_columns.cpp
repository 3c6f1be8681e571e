#include <impactlab/io/event_columns.hpp>

namespace impactlab {

std::string_view column_name(EventColumn column) {
  switch (column) {
    case EventColumn::normal_impulse: return "normal_impulse";
    case EventColumn::tangential_velocity: return "tangential_velocity";
    case EventColumn::normal_force: return "normal_force";
    case EventColumn::friction_work: return "friction_work";
    case EventColumn::instantaneous_residual: return "instantaneous_residual";
    case EventColumn::sliding_residual: return "sliding_residual";
    case EventColumn::tangential_velocity_after: return "tangential_velocity_after";
  }
  return "";
}

EventColumns::EventColumns(std::initializer_list<EventColumn> columns) {
  for (const EventColumn column : columns) present_[static_cast<std::size_t>(column)] = true;
}

EventColumns EventColumns::all() {
  EventColumns columns;
  columns.present_.fill(true);
  return columns;
}

std::vector<std::string_view> EventColumns::names() const {
  std::vector<std::string_view> names = {"t", "kind", "wall", "q", "qdot_before", "qdot_after"};
  for (std::size_t k = 0; k < event_column_count; ++k)
    if (present_[k]) names.push_back(column_name(static_cast<EventColumn>(k)));
  names.push_back("accumulation_error");
  return names;
}

std::string EventColumns::header() const {
  std::string line;
  for (const std::string_view name : names()) {
    if (!line.empty()) line += ',';
    line += name;
  }
  return line + '\n';
}

}  // namespace impactlab
