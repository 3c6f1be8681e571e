// What a simulation run is asked for and what it gives back, independent of
// the oscillator: the event log, optional samples of the state, counters.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/event_log.hpp"

namespace impactlab {

struct RunRequest {
  double t_end = 0.0;        // absolute end time (s); used when periods <= 0
  double periods = 100.0;    // forcing periods to run from t0, when > 0
  double sample_step = 0.0;  // trajectory sampling interval (s); 0: no samples
  bool keep_events = true;
  // called now and then with the fraction of the run done, for progress bars
  std::function<void(double)> progress{};
};

struct TrajectorySample {
  double t;          // s
  double q;          // main coordinate
  double qdot;       // its rate
  std::string_view mode;
};

struct RunOutput {
  std::vector<EventRecord> events;
  std::vector<TrajectorySample> samples;
  double t0 = 0.0, t_end = 0.0;  // the run's time span (s)
  double t_final = 0.0;          // where it stopped (s)
  std::string termination;       // completed, stopped_by_model, no_progress
  std::uint64_t steps = 0, rhs_evaluations = 0;
  std::uint64_t impacts = 0, contact_phases = 0, accumulations = 0, grazings = 0;
  double wall_time = 0.0;        // s
  nlohmann::json derived = nlohmann::json::object();  // oscillator-specific quantities (θ0, ...)
};

}  // namespace impactlab
