#include <impactlab/analysis/periodic_orbits.hpp>

#include <algorithm>

namespace impactlab {

std::string_view to_string(StartOutcome outcome) {
  switch (outcome) {
    case StartOutcome::new_orbit: return "new_orbit";
    case StartOutcome::known_orbit: return "known_orbit";
    case StartOutcome::not_converged: return "not_converged";
    case StartOutcome::stopped: return "stopped";
  }
  return "unknown";
}

int PeriodicOrbitsResult::count(StartOutcome outcome) const {
  return static_cast<int>(std::count(start_outcomes.begin(), start_outcomes.end(), outcome));
}

}  // namespace impactlab
