// Where a Taylor stepper gets its series computed when it runs in a lane of a
// batch (simulate/series_batch.hpp): instead of evaluating its recurrences
// itself, the stepper posts a request and waits; the batch gathers the
// requests of all its lanes and evaluates them (together, in passes over
// lanes, where their operations agree: integrate/series_tape.hpp), then
// hands each lane its coefficients back. The roots that the isolation on the
// witness polynomials refines are requested likewise, and refined in lanes
// together (integrate/monotone_root.hpp). Everything else a step does (its
// size, the exclusion test, the isolation's bounds, the events) stays in the
// lane, in the scalar stepper's own code.
#pragma once

#include <exception>

namespace impactlab {

class SeriesTape;
class SeriesLaneRowsPool;

// the most lanes one batch evaluates together
inline constexpr int max_series_lanes = 16;

// One stepper's request for the series at the start of its step (or, where
// `before_series`, for another computation the lanes share). `evaluate`
// computes `count` requests that share it (they come from steppers of one
// type) together, and writes each one's coefficients into its stepper.
struct SeriesRequest {
  using Evaluate = void (*)(SeriesRequest* const* requests, int count);
  Evaluate evaluate = nullptr;
  // what evaluating this request alone threw (the batch evaluates a group
  // that throws one request at a time): rethrown in the requesting lane
  std::exception_ptr failure;
  // set by `evaluate` where this request's series came from a pass over
  // lanes with others (BatchStatistics::series_in_passes)
  bool in_pass = false;
  // a request that is not for a series (a root's refinement:
  // integrate/monotone_root.hpp): the batch answers these first, and the
  // lanes that made them run on to their next request, so that the series
  // requests still wait together and fill the passes
  bool before_series = false;
  // set by the lane before `evaluate` runs: the lane's tape for the
  // request's order-0 recording, and the batch's rows for its passes over
  // lanes (integrate/series_tape.hpp); made once per batch, so that nothing
  // is allocated while the lanes step
  SeriesTape* tape = nullptr;
  SeriesLaneRowsPool* row_pool = nullptr;
};

// A lane of a batch, as its steppers see it.
class SeriesLane {
 public:
  // Returns once the request's series are computed (the lane is suspended
  // meanwhile, while the other lanes run up to their own requests); rethrows
  // what computing this request threw.
  virtual void compute(SeriesRequest& request) = 0;

 protected:
  SeriesLane() = default;
  SeriesLane(const SeriesLane&) = default;
  SeriesLane& operator=(const SeriesLane&) = default;
  ~SeriesLane() = default;
};

}  // namespace impactlab
