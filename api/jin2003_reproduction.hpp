// The reproduction of Fig. 4 of Jin, Hu & Bishop (2003), computed by the
// toolkit under several impact models of the same scene:
//   (a) the sliding-impact residual "v_c0 − v_y0" (sliding_impact.hpp, the
//       paper's Eqs. 21–22) at the steady-state impacts against ω, V0 fixed;
//   (b) the same against V0, ω fixed;
//   (c) the bob's horizontal displacement x = l sin θ against time;
//   (d) a zoom of (c) on one slip along a wall.
// The steady state follows the paper: the first 200 impacts are discarded.
// The parameter ranges where sliding is possible are derived from (a) and (b)
// by sliding_ranges(), for stated tolerances on the residual, since the
// paper's "close to zero" states none. docs/model-card.md says how each
// quantity reads the garbled source.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <impactlab/io/scene.hpp>
#include <impactlab/simulate/termination.hpp>

namespace impactlab {

struct Jin2003Settings {
  // model specifications: a model name, then scene settings of its own after
  // colons ("rigid:radius=0.01:spin=free"); see api/model_spec.hpp
  std::vector<std::string> models = {"paper", "newton", "rigid:radius=0.01:spin=free"};
  // Fig. 4(a): ω grid (rad/s) at fixed V0 (m/s)
  double omega_from = 6.0, omega_to = 8.0;
  int omega_points = 201;
  double V0_of_fig4a = 1.5;
  // Fig. 4(b): V0 grid (m/s) at fixed ω (rad/s)
  double V0_from = 1.0, V0_to = 5.0;
  int V0_points = 401;
  double omega_of_fig4b = 7.0;
  int transient_impacts = 200;  // discarded, as in the paper
  int recorded_impacts = 50;    // steady-state impacts kept per parameter value
  double periods = 400.0;       // forcing periods simulated per parameter value
  // Fig. 4(c, d): the time history
  double V0_of_history = 4.163, omega_of_history = 7.0;
  double history_periods = 10.0;  // forcing periods shown after the transient
  int threads = 1;
  // called with the fraction of the work done
  std::function<void(double)> progress{};
};

// One steady-state impact of Fig. 4(a) or (b).
struct ResidualRow {
  double parameter;           // ω (rad/s) or V0 (m/s)
  std::string model;
  int k;                      // impact number after the transient, from 0
  double t;                   // s
  int wall;                   // +1 / −1
  double normal_speed;        // v_n = l cos θ0 |θ̇0| (m/s)
  double tangential_velocity; // v_y0, y down (m/s)
  double sliding_residual;    // Eqs. 21–22 (m/s); NaN where V0 ω < g
  double instantaneous_residual;  // Eq. 26 (m/s)
  bool sliding_impact;        // the impact started a sliding phase (Model P)
};

// What one parameter value gave, steady state or not.
struct ParameterSummary {
  double parameter;
  std::string model;
  std::uint64_t impacts;       // in the whole run
  int recorded;                // steady-state impacts kept (≤ recorded_impacts)
  double min_abs_residual;     // over the kept impacts (m/s); NaN if none
  int sliding_impacts;         // kept impacts that started a sliding phase
  Termination termination;
};

struct ResidualPanel {
  std::string parameter;       // "omega" or "V0"
  std::string unit;            // "rad/s" or "m/s"
  std::string fixed;           // the other parameter, "V0" or "omega"
  double fixed_value;
  std::vector<double> grid;
  std::vector<ResidualRow> rows;             // by model, then parameter, then k
  std::vector<ParameterSummary> summaries;   // by model, then parameter
};

struct HistorySample {
  std::string model;
  double t;          // s
  double x;          // l sin θ (m)
  std::string mode;  // free, contact_right, contact_left
};

// The slips of one model in the history window.
struct SlipStatistics {
  std::string model;
  int impacts = 0;
  int contact_phases = 0;       // sliding impacts and post-chatter contacts
  int sliding_impacts = 0;      // contact phases that start at an impact
  double time_on_walls = 0.0;   // s, within the window
  double window = 0.0;          // s
  double mean_slip_duration = 0.0;  // s
};

struct Jin2003Results {
  ResidualPanel fig4a, fig4b;
  std::vector<HistorySample> fig4c, fig4d;
  double history_from = 0.0, history_to = 0.0;  // Fig. 4(c) window (s)
  double zoom_from = 0.0, zoom_to = 0.0;        // Fig. 4(d) window (s)
  std::vector<SlipStatistics> slips;
  double wall_position = 0.0;  // b (m)
  double wall_time = 0.0;      // s
};

// Runs every simulation of the figure set. `scene` is the base scene (the
// built-in jin2003 with any --set applied); its model, V0 and ω are overridden
// per run. Parallel over parameter values; the result does not depend on the
// thread count.
Jin2003Results reproduce_jin2003(const Scene& scene, const Jin2003Settings& settings);

// A closed interval of grid values.
struct ParameterRange {
  double from, to;
};

// The ranges of consecutive grid values where some steady-state impact of
// `model` has |sliding residual| ≤ tolerance (m/s): where the paper's sliding
// condition (Eq. 22) is met to that tolerance.
std::vector<ParameterRange> sliding_ranges(const ResidualPanel& panel, std::string_view model,
                                           double tolerance);

// The tolerances the report derives ranges for (m/s).
const std::vector<double>& report_tolerances();

}  // namespace impactlab
