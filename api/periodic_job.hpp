// `periodic` as a job that any front end runs: the period given or detected
// from the stroboscopic points after the transient, Newton shooting for the
// orbit, and the record periodic.json keeps of it.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include <impactlab/analysis/periodic.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

struct PeriodicJob {
  std::string period = "auto";  // n, or auto: the period of the stroboscopic points
  double phase = 0.0;           // section phase ωt mod 2π (rad)
  double transient = 100.0;     // forcing periods
  int max_iterations = 30;
  double tolerance = 1e-11;
};

struct PeriodicJobResult {
  PeriodicRequest request;
  std::string period_source;  // given, or how it was detected
  PeriodicResult result;
  double wall_time = 0.0;     // s, of the shooting alone
};

// Throws BadInput (key `period`) for a malformed period or an oscillator without the hook.
PeriodicJobResult find_periodic_orbit(const Scene& scene, const PeriodicJob& job);

// periodic.json without the command line, the time of writing and the wall time.
nlohmann::json periodic_record(const Scene& scene, const PeriodicJobResult& job);

}  // namespace impactlab
