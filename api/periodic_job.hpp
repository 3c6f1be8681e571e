// `periodic` as a job that any front end runs: the period given or detected
// from the stroboscopic points after the transient, Newton shooting for the
// orbit, and the record periodic.json keeps of it; with `all`, every orbit of
// the period that deflated Newton shooting finds from starts drawn from a box
// (analysis/periodic_orbits.hpp), the rows of orbits.csv and their record.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <impactlab/analysis/periodic.hpp>
#include <impactlab/analysis/periodic_orbits.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

struct PeriodicJob {
  std::string period = "auto";  // n, or auto: the period of the stroboscopic points
  double phase = 0.0;           // section phase ωt mod 2π (rad)
  double transient = 100.0;     // forcing periods
  int max_iterations = 30;
  double tolerance = 1e-11;
  bool all = false;              // every orbit of the period from `starts` starts (deflation)
  int starts = 20;               // K: starts drawn from the box
  std::vector<std::string> box;  // KEY=FROM:TO each; empty: the default box
  std::uint64_t seed = 1;        // of the starts
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

struct PeriodicOrbitsJobResult {
  PeriodicOrbitsRequest request;
  PeriodicOrbitsResult result;
  double wall_time = 0.0;  // s, of the starts' shooting alone
};

// `periodic --all`: the period given (auto: 1), K ≥ 1 starts from the box
// (`box`, else the default box of api/attractors_job.hpp), deflated Newton
// shooting from each. Every fixed point of Pⁿ is reported with its minimal
// period k (k divides n): an orbit of period 1 is found again as a fixed
// point of P², and listed once. Throws BadInput: a malformed period, K < 1,
// a bad box (key `box`), an oscillator without Jacobians, and no orbit found
// (key `starts`).
// `progress`, where given, is called after each start with the fraction done.
PeriodicOrbitsJobResult find_periodic_orbits(const Scene& scene, const PeriodicJob& job,
                                             const std::function<void(double)>& progress = {});

// One column of orbits.csv: its name, whether it holds whole numbers, its values.
struct OrbitsColumn {
  std::string name;
  bool whole = false;
  std::vector<double> values;
};

// orbits.csv's columns, one row per orbit: id, minimal_period, the state by its
// components' names, impacts and contact_phases per cycle, stable, then
// multiplier1_re, multiplier1_im, ... (of the orbit's own map Pᵏ), residual.
std::vector<OrbitsColumn> periodic_orbits_table(const PeriodicOrbitsJobResult& job);

// periodic.json of `periodic --all` without the command line, the time of
// writing and the wall time: the request (box with units), the units, the
// starts' outcomes and the `orbits` list.
nlohmann::json periodic_orbits_record(const Scene& scene, const PeriodicOrbitsJobResult& job);

}  // namespace impactlab
