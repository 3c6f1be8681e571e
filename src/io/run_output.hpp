// What a simulation run is asked for and what it gives back, independent of
// the oscillator: the event log, optional samples of the state, counters.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <impactlab/core/event_log.hpp>
#include <impactlab/core/event_sink.hpp>
#include <impactlab/io/event_columns.hpp>
#include <impactlab/simulate/termination.hpp>

namespace impactlab {

struct TrajectorySample;

// Receives the trajectory samples of a run as they are taken (a file written
// as the run goes), instead of RunOutput::samples.
class SampleSink {
 public:
  virtual ~SampleSink() = default;
  virtual void write(const TrajectorySample& sample) = 0;
};

struct RunRequest {
  double t_end = 0.0;        // absolute end time (s); used when periods <= 0
  double periods = 100.0;    // forcing periods to run from t0, when > 0
  double sample_step = 0.0;  // trajectory sampling interval (s); 0: no samples
  bool keep_events = true;    // RunOutput::events holds every event (Python, compare)
  // where events and samples go as they happen (files); with a sink the run's
  // memory does not grow with its length. Not owned; may be null.
  EventSink* event_sink = nullptr;
  SampleSink* sample_sink = nullptr;
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
  std::vector<EventRecord> events;          // when RunRequest::keep_events
  std::vector<TrajectorySample> samples;    // when no RunRequest::sample_sink
  std::uint64_t event_count = 0;            // every event, kept or streamed
  std::optional<EventRecord> last_event;    // the last one, if any
  double largest_accumulation_error = 0.0;  // s, 0 when no accumulation
  double t0 = 0.0, t_end = 0.0;  // the run's time span (s)
  double t_final = 0.0;          // where it stopped (s)
  Termination termination = Termination::completed;
  std::uint64_t steps = 0, rhs_evaluations = 0;
  std::uint64_t impacts = 0, contact_phases = 0, accumulations = 0, grazings = 0;
  double wall_time = 0.0;        // s
  nlohmann::json derived = nlohmann::json::object();  // oscillator-specific quantities (θ0, ...)
  // what to do about a run that stopped early, where the oscillator knows
  // (a model file's wall that lacks a sticking table); empty otherwise
  std::string stop_advice;
  // events.csv's columns: the core's and those the run's model fills
  EventColumns event_columns;
};

}  // namespace impactlab
