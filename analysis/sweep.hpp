// Parameter sweeps: 1D bifurcation sweeps that follow the attractor (each
// value starts from the previous value's final state), up, down or both, and
// 2D sweeps whose points are classified (period of the section map, impacts
// per period, contact phases, largest Lyapunov exponent).
//
// The work is cut into tasks whose definition does not depend on the number
// of threads or processes: a task is one continuation run (1D: one direction
// of one chunk of the range; 2D: one row, the first parameter increasing with
// the second fixed). Tasks run in any order on any thread or MPI rank and
// give the same records, so serial, threaded and MPI sweeps write identical
// files.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <impactlab/analysis/initial_box.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/integrate/series_lane.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

// One swept parameter: `count` values from `from` to `to`, both included.
struct SweepAxis {
  std::string name;
  double from = 0.0, to = 0.0;
  int count = 1;
  [[nodiscard]] double value(int index) const;
  // the values increase with the index: `up` (increasing values) walks the
  // indices forwards; FROM > TO walks them backwards
  [[nodiscard]] bool ascending() const { return from <= to; }
};

// Parses NAME=FROM:TO:N; BadInput (key `option`) if malformed.
SweepAxis parse_axis(std::string_view text, std::string_view option);

enum class SweepDirection { up, down, both };
SweepDirection parse_direction(std::string_view text, std::string_view option);
std::string_view to_string(SweepDirection direction);

struct SweepPlan {
  std::vector<SweepAxis> axes;  // one (bifurcation sweep) or two (classification map)
  SweepDirection direction = SweepDirection::up;  // 1D only
  int chunks = 1;               // 1D: continuation runs per direction, each from the scene's start
  SectionRequest section;       // transient, points, section, Lyapunov
  double period_tolerance = 1e-6;  // relative distance under which section points repeat
  int max_period = 16;             // longest period looked for (section-map iterations)
  // each point starts from the previous point's final state (the attractor
  // followed along a row); false: every point from the scene's own initial
  // state, which the axes may set (basins of attraction)
  bool follow_attractor = true;
  double attractor_tolerance = 1e-4;  // basins: relative distance of two attractors' canonical points
  int entropy_box = 5;  // basins: box side of the basin entropies (grid points; analysis/basin_measures.hpp)
  // attractors (samples > 0): at each value of the one axis, `samples`
  // initial states drawn from `box` (analysis/initial_box.hpp, with `seed`);
  // grid index [0] is the value's, [1] the sample's (sweep_tasks)
  int samples = 0;
  std::vector<BoxRange> box;
  std::uint64_t seed = 0;
  double match_tolerance = 0.05;  // attractors: relative distance of point sets at neighbouring values
  // the transient and record of every point stepped at this integrator
  // instead of the scene's (a classification-only sweep, api/sweep_job.hpp);
  // the system's accumulation criteria and the Lyapunov exponent keep the
  // scene's own
  std::optional<IntegratorSetting> classification_integrator;
  std::string classification_note;  // why that integrator, or why the scene's (meta.json)
};

// What a sweep needs of the scene's oscillator: its schema (to validate each
// swept value) and its Poincaré-section run. The scene API supplies it
// (api/scene_jobs.hpp, sweep_target).
struct SweepTarget {
  const SceneSchema* schema = nullptr;
  SectionResult (*section)(const Scene& scene, const SectionRequest& request) = nullptr;
};

// Checks the plan against the scene: the axes name numeric keys of the
// scene's oscillator and every swept value is admissible. Throws BadInput.
void validate_plan(const SweepPlan& plan, const Scene& scene, const SceneSchema& schema);

// One continuation run: grid points (i along axis 1, j along axis 2) in order;
// for a sampled plan (samples > 0) up to samples_per_task consecutive samples
// of one value (i the value's index, j the sample's), the tasks value by
// value, each value's in sample order.
// A sampled plan's samples per task: enough to keep a task's overhead small,
// few enough that threads and MPI ranks share the samples of a single value.
constexpr int samples_per_task = 25;

struct SweepTask {
  int id = 0;
  int direction = 1;  // +1 up, −1 down (1D); +1 in 2D
  std::vector<std::array<int, 2>> points;
};

std::vector<SweepTask> sweep_tasks(const SweepPlan& plan);

// The classification of one point from its section points and counts.
struct Classification {
  int period = 0;                   // smallest p with x_{k+p} ≈ x_k; 0: none up to max_period
  double impacts_per_period = 0.0;  // impacts per forcing period in the record window
  bool contact = false;  // a contact (sticking/sliding) phase in the record window, or all of it
  // the share of the record window's impacts whose impulse stuck (friction
  // stopped the slip: the rigid model); NaN without impacts
  double stick_fraction = std::numeric_limits<double>::quiet_NaN();
};

Classification classify(const SectionResult& result, const SweepPlan& plan);

// Everything a sweep keeps of one point (also one line of a checkpoint).
struct SweepRecord {
  int task = 0, position = 0;  // which task, which point of it
  std::array<int, 2> index{};  // grid indices
  int direction = 1;
  SectionResult result;
  Classification classification;
};

std::string to_json_line(const SweepRecord& record);
// nullopt for a line that does not parse (a line cut short by a kill)
std::optional<SweepRecord> from_json_line(std::string_view line);

// The scene at one grid point. Throws BadInput for an inadmissible value.
Scene scene_at(const Scene& base, const SceneSchema& schema, const SweepPlan& plan,
               const std::array<int, 2>& index);

// Runs one task. `done(position)` returns a finished record to reuse (resume)
// or nullptr; `on_record` receives each new record; `keep_going()` false stops
// the task before its next new point. Returns the task's records in order;
// with `keep_points` false they carry no section points (their count stays in
// result.point_count): a front end that wrote the points out in `on_record`
// then holds one point's worth of them at a time, not the whole sweep's.
// `series_lane`: the batch lane the task runs in (simulate/series_batch.hpp),
// or none; the records are the same either way.
std::vector<SweepRecord> run_sweep_task(
    const Scene& base, const SweepTarget& target, const SweepPlan& plan, const SweepTask& task,
    const std::function<const SweepRecord*(int position)>& done,
    const std::function<void(const SweepRecord&)>& on_record,
    const std::function<bool()>& keep_going, bool keep_points = true,
    SeriesLane* series_lane = nullptr);

// The record without its section points (their count kept).
void drop_points(SweepRecord& record);

}  // namespace impactlab
