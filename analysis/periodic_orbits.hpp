// Every periodic orbit of one period found at one parameter value: the
// type-erased request and result of periodic_orbits_of_scene
// (api/system_jobs.hpp); analysis/run_periodic_orbits.hpp does the work for
// a concrete system with Jacobians. Newton shooting runs from K starts drawn
// reproducibly from a box of initial states (analysis/initial_box.hpp), each
// deflated (analysis/deflation.hpp) by every point of the orbits found before
// it, so that a start that converges finds a new orbit.
#pragma once

#include <complex>
#include <functional>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <impactlab/analysis/initial_box.hpp>
#include <impactlab/simulate/termination.hpp>

namespace impactlab {

struct PeriodicOrbitsRequest {
  int period = 1;             // n: orbits are fixed points of Pⁿ (n forcing periods)
  double phase = 0.0;         // rad: the stroboscopic section ωt ≡ phase (mod 2π)
  int starts = 20;            // K: starts drawn from the box
  std::vector<BoxRange> box;  // the initial-state keys and their ranges (scene keys)
  std::uint64_t seed = 1;     // of the starts (box_value's seed; its point index is 0)
  int max_iterations = 30;    // Newton iterations per start
  double tolerance = 1e-11;   // relative residual |Pⁿ(x) − x| / (1 + |x|)
  // relative distance |x − y| / (1 + |y|) on the tangent space under which two
  // section points are one: an orbit's minimal period (Pᵏ(x) = x), and a
  // converged point that is one of a known orbit's
  double distinct_tolerance = 1e-6;
  bool deflate = true;        // false: plain Newton from every start (for comparison)
  // called after each start with the fraction of starts done (may throw to cancel)
  std::function<void(double)> progress;
};

// One orbit: a fixed point of Pⁿ, with what its minimal period k (k divides
// n) makes of it. Its multipliers are those of Pᵏ, the orbit's own map.
struct FoundPeriodicOrbit {
  int id = 0;                  // 1, 2, ... in the order found
  int minimal_period = 0;      // k: the smallest divisor of n with Pᵏ(x) = x (forcing periods)
  int start = 0;               // the start that found it (0-based)
  std::vector<double> state;   // its point on the section (whole state)
  int mode = 0;
  std::uint64_t impacts = 0;         // impacts over one cycle (k forcing periods)
  std::uint64_t contact_phases = 0;  // sustained contacts begun over one cycle
  std::vector<std::complex<double>> multipliers;  // of Pᵏ, largest modulus first
  bool stable = false;         // every multiplier inside the unit circle
  int iterations = 0;          // Newton iterations of its start
  double residual = 0.0;       // |Pⁿ(x) − x| at convergence
  Termination termination = Termination::completed;  // no_tangent_map: no multipliers
};

// How each start ended.
enum class StartOutcome : std::uint8_t {
  new_orbit,        // converged to an orbit not known before
  known_orbit,      // converged to a point of an orbit already found (deflation can miss)
  not_converged,    // Newton's method ended without converging
  stopped,          // the run to the section or a flow stopped early
};

std::string_view to_string(StartOutcome outcome);

struct PeriodicOrbitsResult {
  bool available = false;  // false: the oscillator/model has no Jacobians (see note)
  std::string note;
  std::vector<std::string> state_names;  // the state's components (core/state_names.hpp)
  std::size_t tangent_dimension = 0;     // N: multipliers per orbit
  double t_section = 0.0;                // s: the section time the orbits' points belong to
  double forcing_period = 0.0;           // T = 2π/ω (s)
  std::vector<FoundPeriodicOrbit> orbits;
  std::vector<StartOutcome> start_outcomes;  // one per start, in order
  std::vector<int> start_orbit;              // the orbit id a start converged to; 0: none
  int count(StartOutcome outcome) const;
};

}  // namespace impactlab
