// The sweep as a job that any front end runs: the plan from its options, the
// tasks over threads with progress, cancellation and reuse of finished points
// (resume), and the records laid out as the rows of bifurcation.csv,
// summary.csv or classes.csv. The CLI adds MPI ranks, the checkpoint files and
// the file writing; the Python module returns the rows as arrays.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <impactlab/analysis/sweep.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

// A sweep as its options state it (the "sweep" table of api/job_options.hpp:
// param, direction, ...); BadInput names the options by those names.
struct SweepSpec {
  std::vector<std::string> params;  // NAME=FROM:TO:N, one or two
  std::string direction = "up";     // up | down | both (1D)
  int chunks = 1;
  SectionRequest section;
  std::optional<bool> lyapunov;  // unset: on for 2D maps, off for 1D sweeps
  double period_tolerance = 1e-6;
  int max_period = 16;
  // auto: a sweep that only classifies (a 2D map) integrates at the scene's
  // integrator.classification_* where it states them and no integrator key
  // was set by the user; off: always the scene's integrator
  std::string classification_tolerance = "auto";
  // the option that gave `params` in BadInput messages (basins: "x/y")
  std::string param_key = "param";
};

// The validated plan. Throws BadInput, among others (key `param`) for a
// swept key the scene's model does not read (api/model_keys.hpp).
SweepPlan make_sweep_plan(const SweepSpec& spec, const Scene& scene, const SceneSchema& schema);

// Everything that decides the sweep's results (not threads or ranks): the
// checkpoint header and meta.json's "sweep". `section_record`: the section
// options as the front end states them.
nlohmann::json sweep_definition(const SweepPlan& plan, const Scene& scene,
                                const SceneSchema& schema, const nlohmann::json& section_record);

using SweepRecordKey = std::pair<int, int>;  // task, position

struct SweepJobOptions {
  int threads = 1;
  // finished records to reuse (resume), by key
  const std::map<SweepRecordKey, SweepRecord>* done = nullptr;
  // each new record, under the job's lock (a checkpoint line)
  std::function<void(const SweepRecord&)> on_record{};
  // fraction of this job's points finished, under the job's lock; may throw
  // to cancel the sweep (the exception comes out of run_sweep)
  std::function<void(double)> progress{};
  long stop_after = 0;  // > 0: stop after this many new points (tests of resume)
  // false: the records kept (SweepOutput) carry no section points, only their
  // count; for a front end that streams the points out in on_record
  bool keep_points = true;
  // on: where the sweep's stepper is taylor, its tasks run in the lanes of a
  // batch on each thread, their series computed together
  // (simulate/series_batch.hpp); off: one task at a time on each thread.
  // The records are the same either way.
  std::string batch = "on";
};

struct SweepOutput {
  std::vector<std::vector<SweepRecord>> records;  // per task given, in order
  bool stopped = false;                           // stop_after ended it early
  int batch_width = 1;  // lanes per thread (sweep_batch_width; meta.json)
};

// The lanes a sweep's batch runs per thread: default_batch_width where
// `batch` is on and the transient and record, or the Lyapunov run, step
// with taylor; 1 otherwise (no batch). BadInput (`batch`) for a value other
// than on or off.
int sweep_batch_width(const Scene& scene, const SweepPlan& plan, const std::string& batch);

// Runs `tasks` (all of the plan's, or one MPI rank's share) on threads.
SweepOutput run_sweep(const Scene& scene, const SweepTarget& target, const SweepPlan& plan,
                      const std::vector<const SweepTask*>& tasks, const SweepJobOptions& options);

// The records of a whole sweep as table rows: a 1D sweep gives section points
// (bifurcation.csv) and one summary row per value and direction (summary.csv);
// a 2D map gives one summary row per grid point (classes.csv).
struct SweepTable {
  // bifurcation rows
  std::vector<double> point_value, point_t, point_q, point_qdot;
  std::vector<int> point_k, point_wall, point_direction;
  // summary (1D) or classes (2D) rows
  std::vector<double> value, value2;  // value2: 2D only
  std::vector<int> direction;         // 1D: +1 up, -1 down
  std::vector<int> period;
  std::vector<double> impacts_per_period, lyapunov;
  std::vector<int> contact;
  std::vector<SectionTermination> termination;
  std::vector<int> points;
  std::vector<double> stick_fraction;  // impacts that stuck / impacts; NaN without impacts
  std::vector<double> transient_periods;  // forcing periods the point's transient ran
  std::vector<TransientEnd> transient_end;
  // with the spectrum asked for: N exponents per row (1/time unit, −∞
  // collapsed, NaN not computed), row-major, rows × lyapunov_dimension
  std::size_t lyapunov_dimension = 0;
  std::vector<double> lyapunov_spectrum;
};

// N of a sweep's spectrum: the exponents its records hold (0 where the plan
// does not ask for them).
std::size_t lyapunov_dimension(const SweepPlan& plan,
                               const std::map<SweepRecordKey, SweepRecord>& records);

// A record's N exponents appended to `columns` (NaN for those it lacks).
void add_lyapunov_spectrum(std::vector<double>& columns, std::size_t dimension,
                           const SweepRecord& record);

SweepTable sweep_table(const SweepPlan& plan, const std::vector<SweepTask>& tasks,
                       const std::map<SweepRecordKey, SweepRecord>& records);

// The records in the order of the table's rows: a 1D sweep's upward records
// by increasing value, then its downward ones by decreasing value; a 2D map's
// task by task. A front end that streams bifurcation rows reads the records'
// points in this order.
std::vector<SweepRecordKey> sweep_row_order(const SweepPlan& plan,
                                            const std::vector<SweepTask>& tasks);

// What a finished sweep's records count (meta.json's "counts"): points,
// points_stopped_early (termination other than completed),
// points_not_settled (transient_end not_settled), steps and rhs_evaluations
// summed over the points.
nlohmann::json sweep_counts(const std::map<SweepRecordKey, SweepRecord>& records);

// The points that stopped early and why, for the run's summary: "7 of 20
// points stopped early (no_progress 7)"; empty where every point completed.
std::string stopped_points_note(const std::map<SweepRecordKey, SweepRecord>& records);

// The points whose transient was still converging when it ran out, for the
// run's summary: "3 of 400 points did not settle within max_transient = 2000
// forcing periods: their periods may be a transient's"; empty where none.
std::string unsettled_points_note(const std::map<SweepRecordKey, SweepRecord>& records,
                                  const SweepPlan& plan);

// A 1D sweep's bifurcation rows of one record (its section points).
void add_bifurcation_rows(SweepTable& table, const SweepPlan& plan, const SweepRecord& record);

}  // namespace impactlab
