// The explorer's requests (`impactlab explore`, Python's impactlab.explore):
// a served page's JSON turned into the scene API's jobs (simulate, poincare,
// the sweep, the periodic job) and their results into JSON, with the bounds
// one request may ask for. The HTTP server is plumbing around these; every
// number the page shows comes from the same functions the CLI and Python call.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <impactlab/io/scene.hpp>

namespace impactlab {

// What one request may ask for: the work a page can start is bounded by these.
struct ExploreLimits {
  std::size_t max_body_bytes = 64 * 1024;   // a request's body (bytes)
  std::size_t max_value_chars = 200;        // one scene value's text
  double max_periods = 5000.0;              // forcing periods of a time series or transient
  double max_samples = 200000.0;            // samples of one time series
  std::uint64_t max_section_points = 5000;  // points of one section
  int max_columns = 1000;                   // parameter values of one orbit diagram
  std::uint64_t max_column_points = 500;    // section points per diagram column
  int max_threads = 16;                     // worker threads of one orbit diagram
  int max_live_jobs = 8;                    // jobs running at once, superseded ones included
};

// What the page needs of the scene: its name, oscillator, main coordinate
// and each key of its schema with unit, help, range (or choices) and value;
// `slider` is true for a number with a finite range.
nlohmann::json explore_scene_description(const Scene& scene);

// `base` with the page's values ({"V0": 4.1, "model": "paper", ...}) applied
// through apply_override: only the scene's own keys and values its own
// validation accepts (BadInput with the scene's message otherwise).
Scene explore_scene(const Scene& base, const nlohmann::json& values, const ExploreLimits& limits);

// The views the page draws, each one scene API job. Their options come from
// the request's "options" object; BadInput names an option outside its bound.
struct TrajectoryView {                 // impactlab simulate --periods P --sample DT
  double periods = 20.0;                // forcing periods from t0
  int samples_per_period = 64;
};
struct SectionView {                    // impactlab poincare --transient T --points N
  double transient = 100.0;             // forcing periods discarded, exactly
  std::uint64_t points = 300;
};
struct DiagramView {                    // impactlab sweep --param KEY=FROM:TO:N
  std::string key;
  double from = 0.0, to = 0.0;
  int columns = 200;
  double transient = 100.0;             // forcing periods discarded at each value
  std::uint64_t points = 32;            // section points per value
  int threads = 1;
};
struct OrbitView {                      // impactlab periodic, poincare --lyapunov
  // the clicked point of a diagram: the parameter value and the section point
  // (t, q, qdot) the orbit search starts from; key empty: the scene's own start
  std::string key;
  double value = 0.0;
  double t = 0.0;     // time of the section point (scene time unit)
  double q = 0.0;     // main coordinate there (θ in rad, x or y in m)
  double qdot = 0.0;  // its rate (per scene time unit)
  double transient = 100.0;             // forcing periods before the orbit search
  std::uint64_t lyapunov_points = 200;  // section points the exponent averages over
};

TrajectoryView trajectory_view(const nlohmann::json& options, const ExploreLimits& limits);
SectionView section_view(const nlohmann::json& options, const ExploreLimits& limits);
DiagramView diagram_view(const nlohmann::json& options, const Scene& scene,
                         const ExploreLimits& limits);
OrbitView orbit_view(const nlohmann::json& options, const Scene& scene,
                     const ExploreLimits& limits);

// The scene of an orbit view: the parameter value set and the run started
// from the clicked section point (t0 and the initial main coordinate and its
// rate, where the scene has those keys).
Scene orbit_scene(const Scene& scene, const OrbitView& view);

// How a running view reports: `progress` gets the fraction done and may throw
// to cancel; `add_column` (diagram) gets each finished column as it comes.
struct ExploreProgress {
  std::function<void(double)> progress;
  std::function<void(const nlohmann::json&)> add_column;
};

// The views' results as JSON: series as arrays of numbers.
// trajectory: t, q, qdot (samples), impacts {t, q, wall}, walls, termination
nlohmann::json run_trajectory(const Scene& scene, const TrajectoryView& view,
                              const ExploreProgress& report);
// section: t, q, qdot, termination
nlohmann::json run_section(const Scene& scene, const SectionView& view,
                           const ExploreProgress& report);
// diagram: each column {value, t, q, qdot, period} handed to add_column as
// it is finished; the result counts them
nlohmann::json run_diagram(const Scene& scene, const DiagramView& view,
                           const ExploreProgress& report);
// orbit: periodic.json's record, the orbit's trajectory over its period
// (t, q, qdot) and the largest Lyapunov exponent at the point
nlohmann::json run_orbit(const Scene& scene, const OrbitView& view,
                         const ExploreProgress& report);

// The export of a view: the scene file (scene_file_text), the command lines
// and the Python calls that reproduce it. `scene_source`: the scene as the
// server was given it (a built-in name or a path); `base` that scene as
// loaded, so that only the keys the page changed are set.
struct ExploreExport {
  std::string scene_toml;
  std::vector<std::vector<std::string>> commands;  // argv, without an output folder
  std::vector<std::string> python_calls;
};
ExploreExport explore_export(const std::string& view_kind, const nlohmann::json& options,
                             const std::string& scene_source, const Scene& base,
                             const Scene& scene, const ExploreLimits& limits);

// A command's words joined for a POSIX shell, each quoted where it needs it.
std::string shell_command(const std::vector<std::string>& words);

}  // namespace impactlab
