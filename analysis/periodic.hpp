// A periodic orbit located from a scene: the type-erased request and result of
// periodic_orbit_of_scene (api/system_jobs.hpp) (analysis/run_periodic.hpp does the work for
// a concrete system with Jacobians).
#pragma once

#include <complex>
#include <limits>
#include <string>
#include <vector>

#include <impactlab/simulate/termination.hpp>

namespace impactlab {

struct PeriodicRequest {
  int period = 1;                 // n: the orbit's period in forcing periods
  double phase = 0.0;             // rad: the stroboscopic section ωt ≡ phase (mod 2π)
  double transient_periods = 100; // periods run from the scene's initial state first
  int max_iterations = 30;        // Newton iterations
  double tolerance = 1e-11;       // relative residual |Pⁿ(x) − x| / (1 + |x|)
};

struct PeriodicResult {
  bool available = false;  // false: the oscillator/model has no Jacobians (see note)
  std::string note;
  std::vector<double> state;      // the orbit's point on the section (whole state)
  std::vector<std::string> state_names;  // its components' names (core/state_names.hpp)
  int mode = 0;
  double t_section = 0.0;         // the section time the point belongs to
  double orbit_period = 0.0;      // nT
  // on the system's tangent space: N × N, row-major (N = 2: (q, q̇); a model
  // file: its N states), and its N eigenvalues, largest modulus first (none
  // where Newton's method did not converge: the state is then no orbit)
  std::vector<std::vector<double>> monodromy;
  std::vector<std::complex<double>> multipliers;
  bool converged = false;
  int iterations = 0;
  double residual = std::numeric_limits<double>::quiet_NaN();
  Termination termination = Termination::completed;
  std::string failure;  // why Newton's method ended unconverged; empty where it converged
};

}  // namespace impactlab
