// Basins of attraction as a job that any front end runs (the CLI's
// `impactlab basins`, the Python module's basins): the plan from the two grid
// keys, a sweep whose points each start from the scene's state
// (SweepPlan::follow_attractor false, run by api/sweep_job.hpp's run_sweep),
// and its records classified by attractor (analysis/basins.hpp) and laid out
// as the rows of basins.csv and attractors.csv.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <impactlab/analysis/basin_measures.hpp>
#include <impactlab/analysis/basins.hpp>
#include <impactlab/api/sweep_job.hpp>

namespace impactlab {

// A basins map as its options state it (the "basins" table of
// api/job_options.hpp); BadInput names the options by those names (x, y,
// attractor_tol, entropy_box; x/y for the grid as a whole).
struct BasinsSpec {
  std::string x, y;  // KEY=FROM:TO:N: the first (fastest) and second grid key
  SectionRequest section;
  bool lyapunov = false;
  double period_tolerance = 1e-6;
  int max_period = 16;
  double attractor_tolerance = 1e-4;  // relative distance of two canonical points
  // box side of the basin entropies (grid points); unset: 5, or the grid's
  // shorter side where that is smaller; one given must fit in the grid
  std::optional<int> entropy_box;
};

// The box side an unset entropy_box takes (grid points): 5 × 5 boxes, as
// Daza et al. (2016) use, hold enough points for a box's label shares while
// staying small against the grid.
constexpr int default_entropy_box = 5;

// The validated plan: both keys numeric keys of the scene's oscillator that
// its model reads (api/model_keys.hpp), and different, every point from the
// scene's state. Throws BadInput.
SweepPlan make_basins_plan(const BasinsSpec& spec, const Scene& scene, const SceneSchema& schema);

// sweep_definition with the basins' own entries (the checkpoint header and
// meta.json's "sweep").
nlohmann::json basins_definition(const SweepPlan& plan, const Scene& scene,
                                 const SceneSchema& schema, const nlohmann::json& section_record);

// The rows of basins.csv (one per grid point, in grid order: the first key
// fastest) and the attractors of attractors.csv.
struct BasinsTable {
  std::vector<double> x, y;
  std::vector<int> attractor, period;
  std::vector<double> impacts_per_period;
  std::vector<int> contact;
  std::vector<SectionTermination> termination;
  std::vector<TransientEnd> transient_end;
  // with the spectrum asked for: N exponents per row, row-major (sweep_job.hpp)
  std::size_t lyapunov_dimension = 0;
  std::vector<double> lyapunov_spectrum;
  BasinMap map;  // the attractors (by id) and the count of unclassified points
  BasinMeasures measures;  // the label grid's entropies and uncertainty exponent
};

BasinsTable basins_table(const SweepPlan& plan, const std::vector<SweepTask>& tasks,
                         const std::map<SweepRecordKey, SweepRecord>& records);

// The rows of attractors.csv: attractor 0 (the grid points that settled on
// none: period 0, no impact rate or point) first where there are any, then
// each attractor by id with its canonical section point (q, qdot).
struct AttractorRows {
  std::vector<int> id, period, contact, basin_points;
  std::vector<double> impacts_per_period, q, qdot;
};

AttractorRows attractor_rows(const BasinMap& map);

// meta.json's "basin_measures" (the CLI's and Python's alike): each number
// with its meaning and unit, the box size and the scales; nan as null.
nlohmann::json basin_measures_record(const BasinMeasures& measures);

// The one line the CLI prints after its summary: S_b, S_bb and α ± its error.
std::string basin_measures_line(const BasinMeasures& measures);

}  // namespace impactlab
