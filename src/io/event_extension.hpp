// What a model adds to the record of an event beyond the core's fields
// (core/event_log.hpp knows what every model computes): the columns of
// events.csv that only some models fill, and the fields of the same names in
// Python's events array. The writer asks for each event's extension where
// the run's model has one (the scene API's event_extender,
// api/scene_jobs.hpp).
#pragma once

#include <functional>
#include <limits>

#include <impactlab/core/event_log.hpp>

namespace impactlab {

// NaN: not computed (an empty field in events.csv).
struct EventExtension {
  // the pendulum's Model P at an impact (oscillators/pendulum_walls/sliding_impact.hpp):
  double instantaneous_residual = std::numeric_limits<double>::quiet_NaN();  // Eq. 26 (m/s)
  double sliding_residual = std::numeric_limits<double>::quiet_NaN();  // Eqs. 21-22 (m/s)
};

// The extension of one event of a run; empty where the model has none.
using EventExtender = std::function<EventExtension(const EventRecord& event)>;

}  // namespace impactlab
