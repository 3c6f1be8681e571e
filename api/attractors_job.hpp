// Attractors found and followed across a parameter, as a job that any front
// end runs (the CLI's `impactlab attractors`, the Python module's
// attractors): the plan (one parameter axis, K initial states per value drawn
// reproducibly from a box, analysis/initial_box.hpp), a sweep whose points
// each start from their own sampled state (SweepPlan::follow_attractor false,
// run by api/sweep_job.hpp's run_sweep, up to samples_per_task samples of one
// value per task), and its records told apart and followed
// (analysis/attractor_following.hpp) and laid out as the rows of
// attractors.csv, attractor_points.csv and samples.csv.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <impactlab/analysis/attractor_following.hpp>
#include <impactlab/api/sweep_job.hpp>

namespace impactlab {

// The attractors job as its options state it (the "attractors" table of
// api/job_options.hpp); BadInput names the options by those names (param,
// samples, box, attractor_tol, match_tol).
struct AttractorsSpec {
  std::string param;              // NAME=FROM:TO:N
  int samples = 100;              // K: initial states per value
  std::vector<std::string> box;   // KEY=FROM:TO each; empty: the default box
  std::uint64_t seed = 1;
  SectionRequest section;
  bool lyapunov = false;
  double period_tolerance = 1e-6;
  int max_period = 16;
  double attractor_tolerance = 1e-4;  // relative distance of two canonical points (one value)
  double match_tolerance = 0.05;      // relative Hausdorff distance of point sets (neighbouring values)
};

// The box an empty `box` option takes: every initial-state key of the
// scene's oscillator that its model reads (initial.<state>), each over
// [v − h, v + h] around the scene's value v, h = 1 in the key's unit, halved
// until every corner of the box is a state the oscillator accepts (the
// pendulum's inside the walls, the ball on or above the table); where no h
// down to 2^−40 is accepted (v on the edge of the accepted states), the
// upper side [v, v + h], then the lower one [v − h, v], halved the same way.
// BadInput (key `box`) where none is accepted.
std::vector<BoxRange> default_box(const Scene& scene, const SceneSchema& schema);

// The box the `box` option gives: each KEY=FROM:TO parsed, its key a numeric
// key the model reads, given once; the default box where none is given.
// Throws BadInput (key `box`).
std::vector<BoxRange> box_of_options(const std::vector<std::string>& options,
                                     const Scene& scene, const SceneSchema& schema);

// BadInput (key `box`) where a corner of the box is a state the oscillator
// refuses in `scene`; `where` (such as "omega = 2") says which scene, empty
// for the scene as given.
void refuse_box_corners(const Scene& scene, const SceneSchema& schema,
                        const std::vector<BoxRange>& box, const std::string& where);

// The validated plan: the parameter a numeric key its model reads, K ≥ 1, each
// box key a numeric key read by the model, given once, not the parameter, and
// every corner of the box at both ends of the parameter a state the
// oscillator accepts. Throws BadInput.
SweepPlan make_attractors_plan(const AttractorsSpec& spec, const Scene& scene,
                               const SceneSchema& schema);

// sweep_definition with the attractors' own entries (the checkpoint header and
// meta.json's "sweep"): samples, box (keys, units, ranges), seed and both
// tolerances.
nlohmann::json attractors_definition(const SweepPlan& plan, const Scene& scene,
                                     const SceneSchema& schema,
                                     const nlohmann::json& section_record);

// The attractors of every value, followed, and the rows of the three files.
struct AttractorsTable {
  std::vector<AttractorsAtValue> values;  // in parameter order
  std::vector<AttractorEvent> events;
  // attractors.csv: per value, attractor 0 (the samples that settled on none)
  // where there are any, then each attractor by id
  struct Rows {
    std::vector<double> value;
    std::vector<int> id, period, impacts_per_cycle, contact, samples;
    std::vector<double> impacts_per_period, contact_phases_per_period, min_impact_speed, q,
        qdot, lyapunov, fraction, fraction_error;
  } attractors;
  // attractor_points.csv: each attractor's cycle, k = 0 … period − 1
  struct Points {
    std::vector<double> value, q, qdot;
    std::vector<int> id, k;
  } points;
  // samples.csv: every sample, in parameter then sample order
  struct Samples {
    std::vector<double> value;
    std::vector<int> sample;
    std::vector<std::vector<double>> box;  // per box key: the sample's initial value
    std::vector<int> attractor, period, contact;
    std::vector<double> impacts_per_period;
    std::vector<SectionTermination> termination;
    std::vector<TransientEnd> transient_end;
  } samples;
};

AttractorsTable attractors_table(const SweepPlan& plan, const std::vector<SweepTask>& tasks,
                                 const std::map<SweepRecordKey, SweepRecord>& records);

// meta.json's "attractor_events": each change with the parameter's values
// either side of it, and what the entries mean.
nlohmann::json attractor_events_record(const AttractorsTable& table, const SweepPlan& plan);

// The one line the CLI prints after its summary: how many attractors, and
// the events.
std::string attractors_line(const AttractorsTable& table);

}  // namespace impactlab
