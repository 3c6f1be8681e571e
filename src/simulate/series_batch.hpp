// Many trajectories on one thread, their Taylor series computed together.
//
// run_in_lanes runs jobs in `width` lanes, each lane a fiber (a stack of its
// own, switched on this thread: no threads, no locks). A job is ordinary
// simulation code whose steppers carry the lane in their settings
// (StepperSettings::series_lane): each Taylor step suspends its lane where it
// needs its series (integrate/series_lane.hpp). When every lane waits, the
// batch evaluates the waiting requests (in passes over lanes where their
// order-0 tapes record the same operations: integrate/series_tape.hpp,
// TaylorStepper's evaluate_requests), and resumes each lane with its own
// coefficients; the lane then finishes its step alone, in the scalar
// stepper's own code: step size, exclusion test, root isolation, events. The
// roots the isolation refines are requests too, answered before any series
// (SeriesRequest::before_series), the roots of the lanes that ask in one
// round refined together (integrate/monotone_root.hpp).
// A lane whose job ends takes the next job at once, so no lane waits for
// the slowest. Each lane's run is the scalar run of its job, to the last bit.
//
// A stepper other than Taylor never suspends: its lane runs its job through
// without batching (correct, no faster).
#pragma once

#include <cstddef>
#include <cstdint>

#include <impactlab/integrate/series_lane.hpp>
#include <impactlab/platform/function_ref.hpp>

namespace impactlab {

// the lanes a batch runs by default: the most it may, so that as many
// requests as possible wait together and the passes over lanes fill
// (a pass takes up to eight, integrate/series_tape.hpp; when passes took
// four, a batch of 4 lanes evaluated a 2D map's Lyapunov runs, a phase that
// only some lanes are in at a time, mostly alone: docs/performance.md)
inline constexpr int default_batch_width = max_series_lanes;

// the rounds a lone series request waits for a partner by default
// (run_in_lanes): on a 2D map with Lyapunov exponents, 32 rounds ran 8.7 %
// fewer instructions than none and 8 rounds 7.6 % (docs/performance.md,
// "a lone series waits for a partner")
inline constexpr int default_lone_wait_rounds = 32;

// How full the batch ran: how many series it evaluated, in how many
// evaluations together (lane_series / evaluations: the mean lanes per
// evaluation, at most the width), and how many of them in passes over lanes
// (integrate/series_tape.hpp) rather than alone.
// The requests that come before the series (SeriesRequest::before_series:
// roots' refinements) are counted apart: `early_requests` of them in
// `early_evaluations` evaluations together.
struct BatchStatistics {
  std::uint64_t evaluations = 0;
  std::uint64_t lane_series = 0;
  std::uint64_t series_in_passes = 0;
  std::uint64_t early_evaluations = 0;
  std::uint64_t early_requests = 0;
};

// Calls run_next_job(lane) in each of `width` lanes (1 <= width <=
// max_series_lanes) until it returns false in every lane: it takes the next
// job, runs it with the lane in its steppers' settings, and returns true, or
// returns false when no job is left. Returns when every lane has finished;
// rethrows the first exception a lane's run_next_job threw (that lane stops
// taking jobs; the others finish theirs). The fibers' stacks are made once
// per call: nothing is allocated while the lanes step.
//
// A lane whose series request is the only one of its kind (steppers of its
// type) in a round, while other lanes' requests share theirs, waits for up
// to `lone_wait_rounds` rounds in a row (its lane does not run meanwhile)
// for another lane to ask for a series of its kind: a series alone costs
// several times a lane of a pass, and a lane that starts a phase of its
// own (a 2D map's point reaching its Lyapunov run, the variational
// system's steps) is then soon joined by the next. Waiting changes no
// lane's numbers, only the order in which the lanes run; 0: no waiting.
BatchStatistics run_in_lanes(int width, FunctionRef<bool(SeriesLane& lane)> run_next_job,
                             int lone_wait_rounds = default_lone_wait_rounds);

}  // namespace impactlab
