#include <impactlab/api/periodic_job.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>

#include <fmt/format.h>

#include <impactlab/analysis/deflation.hpp>
#include <impactlab/analysis/sweep.hpp>
#include <impactlab/api/attractors_job.hpp>
#include <impactlab/api/job_options.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/system_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/scene_record.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace {

nlohmann::json complex_record(std::complex<double> z) {
  return {{"re", z.real()}, {"im", z.imag()}, {"abs", std::abs(z)}};
}

// n from the period option: a whole number from 1 to 1000; BadInput (key `period`)
int period_of(const std::string& text) {
  char* end = nullptr;
  const long n = std::strtol(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0' || n < 1 || n > 1000)
    throw BadInput("period", text, "expected auto or a whole number from 1 to 1000");
  return static_cast<int>(n);
}

// the unit of a scene key in the schema; empty where it has none
std::string unit_of(const SceneSchema& schema, const std::string& key) {
  const auto spec = std::find_if(schema.keys.begin(), schema.keys.end(),
                                 [&](const KeySpec& k) { return k.key == key; });
  return spec == schema.keys.end() ? std::string() : std::string(spec->unit);
}

}  // namespace

PeriodicJobResult find_periodic_orbit(const Scene& scene, const PeriodicJob& job) {
  PeriodicJobResult out;
  PeriodicRequest& request = out.request;
  out.period_source = "given";
  if (job.period == "auto") {
    // the period of 64 stroboscopic points after the transient (1 if none is found)
    SectionRequest probe;
    probe.section.phase = job.phase;
    probe.transient_periods = job.transient;
    probe.settle = false;  // the orbit search starts after exactly job.transient periods
    probe.points = 64;
    SweepPlan plan;
    plan.max_period = 32;
    const SectionResult points = poincare(scene, probe);
    const int detected = classify(points, plan).period;
    request.period = detected > 0 ? detected : 1;
    out.period_source = detected > 0 ? "detected from 64 stroboscopic points"
                                     : "not detected in 64 stroboscopic points: 1 tried";
  } else {
    request.period = period_of(job.period);
  }
  request.phase = job.phase;
  request.transient_periods = job.transient;
  request.max_iterations = job.max_iterations;
  request.tolerance = job.tolerance;
  const auto start = std::chrono::steady_clock::now();
  out.result = periodic(scene, request);
  out.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!out.result.available) throw BadInput("oscillator", scene.oscillator, out.result.note);
  return out;
}

nlohmann::json periodic_record(const Scene& scene, const PeriodicJobResult& job) {
  const PeriodicRequest& request = job.request;
  const PeriodicResult& result = job.result;
  nlohmann::json multipliers = nlohmann::json::array();
  for (const auto& multiplier : result.multipliers) multipliers.push_back(complex_record(multiplier));
  return {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"scene", scene_record(scene)},
      {"request",
       {{"period", request.period},
        {"period_source", job.period_source},
        {"phase_rad", request.phase},
        {"transient_periods", request.transient_periods},
        {"max_iterations", request.max_iterations},
        {"tolerance", request.tolerance}}},
      {"converged", result.converged},
      {"failure", result.failure},
      {"iterations", result.iterations},
      {"residual", result.residual},
      {"termination", to_string(result.termination)},
      {"t_section", result.t_section},
      {"orbit_period", result.orbit_period},
      {"state", result.state},
      {"state_names", result.state_names},
      {"mode", result.mode},
      {"monodromy", result.monodromy},
      {"floquet_multipliers", multipliers},
  };
}

PeriodicOrbitsJobResult find_periodic_orbits(const Scene& scene, const PeriodicJob& job,
                                             const std::function<void(double)>& progress) {
  PeriodicOrbitsJobResult out;
  PeriodicOrbitsRequest& request = out.request;
  request.period = job.period == "auto" ? 1 : period_of(job.period);
  if (job.starts < 1)
    throw BadInput("starts", std::to_string(job.starts), "must be a whole number >= 1");
  const SceneSchema& schema = scene_schema(scene);
  request.box = box_of_options(job.box, scene, schema);
  // the orbits of one system: its parameters stay as the scene has them
  for (const BoxRange& range : request.box)
    if (!range.key.starts_with("initial."))
      throw BadInput("box", range.key + "=" + fmt::format("{}:{}", range.from, range.to),
                     fmt::format("periodic {} draws initial states: {} is not an initial.* key",
                                 mention("all"), range.key));
  refuse_box_corners(scene, schema, request.box, "");
  request.phase = job.phase;
  request.starts = job.starts;
  request.seed = job.seed;
  request.max_iterations = job.max_iterations;
  request.tolerance = job.tolerance;
  request.progress = progress;
  const auto start = std::chrono::steady_clock::now();
  out.result = periodic_orbits_of_scene(scene, request);
  request.progress = nullptr;  // the caller's, not the result's
  out.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!out.result.available) throw BadInput("oscillator", scene.oscillator, out.result.note);
  if (out.result.orbits.empty())
    throw BadInput("starts", std::to_string(request.starts),
                   fmt::format("periodic {}: no orbit of period {} from {} starts ({} did not "
                               "converge, {} stopped early); try more {}, another {} or {}",
                               mention("all"), request.period, request.starts,
                               out.result.count(StartOutcome::not_converged),
                               out.result.count(StartOutcome::stopped), mention("starts"),
                               mention("box"), mention("seed")));
  return out;
}

std::vector<OrbitsColumn> periodic_orbits_table(const PeriodicOrbitsJobResult& job) {
  const PeriodicOrbitsResult& result = job.result;
  std::vector<OrbitsColumn> columns;
  const auto column = [&](std::string name, bool whole, auto value_of) {
    OrbitsColumn c{std::move(name), whole, {}};
    for (const FoundPeriodicOrbit& orbit : result.orbits) c.values.push_back(value_of(orbit));
    columns.push_back(std::move(c));
  };
  column("id", true, [](const FoundPeriodicOrbit& o) { return o.id; });
  column("minimal_period", true, [](const FoundPeriodicOrbit& o) { return o.minimal_period; });
  for (std::size_t k = 0; k < result.state_names.size(); ++k)
    column(result.state_names[k], false, [k](const FoundPeriodicOrbit& o) { return o.state[k]; });
  column("impacts", true,
         [](const FoundPeriodicOrbit& o) { return static_cast<double>(o.impacts); });
  column("contact_phases", true,
         [](const FoundPeriodicOrbit& o) { return static_cast<double>(o.contact_phases); });
  column("stable", true, [](const FoundPeriodicOrbit& o) { return o.stable ? 1.0 : 0.0; });
  for (std::size_t k = 0; k < result.tangent_dimension; ++k) {
    column(fmt::format("multiplier{}_re", k + 1), false,
           [k](const FoundPeriodicOrbit& o) { return o.multipliers[k].real(); });
    column(fmt::format("multiplier{}_im", k + 1), false,
           [k](const FoundPeriodicOrbit& o) { return o.multipliers[k].imag(); });
  }
  column("residual", false, [](const FoundPeriodicOrbit& o) { return o.residual; });
  return columns;
}

nlohmann::json periodic_orbits_record(const Scene& scene, const PeriodicOrbitsJobResult& job) {
  const PeriodicOrbitsRequest& request = job.request;
  const PeriodicOrbitsResult& result = job.result;
  const SceneSchema& schema = scene_schema(scene);
  nlohmann::json box = nlohmann::json::array();
  for (const BoxRange& range : request.box)
    box.push_back({{"key", range.key},
                   {"unit", unit_of(schema, range.key)},
                   {"from", range.from},
                   {"to", range.to}});
  nlohmann::json units = {{"t_section", "s"}, {"forcing_period", "s"},
                          {"minimal_period", "forcing periods"},
                          {"impacts", "per cycle (minimal_period forcing periods)"},
                          {"contact_phases", "per cycle (minimal_period forcing periods)"},
                          {"multipliers", "dimensionless, of the orbit's own map P^k"},
                          {"residual", "|P^n(x) - x| in the state's units"}};
  for (const std::string& name : result.state_names)
    units[name] = unit_of(schema, "initial." + name);
  nlohmann::json orbits = nlohmann::json::array();
  for (const FoundPeriodicOrbit& orbit : result.orbits) {
    nlohmann::json multipliers = nlohmann::json::array();
    for (const auto& multiplier : orbit.multipliers)
      multipliers.push_back(complex_record(multiplier));
    orbits.push_back({{"id", orbit.id},
                      {"minimal_period", orbit.minimal_period},
                      {"state", orbit.state},
                      {"mode", orbit.mode},
                      {"impacts", orbit.impacts},
                      {"contact_phases", orbit.contact_phases},
                      {"stable", orbit.stable},
                      {"floquet_multipliers", multipliers},
                      {"termination", to_string(orbit.termination)},
                      {"start", orbit.start},
                      {"iterations", orbit.iterations},
                      {"residual", orbit.residual}});
  }
  nlohmann::json outcomes = nlohmann::json::array();
  for (const StartOutcome outcome : result.start_outcomes) outcomes.push_back(to_string(outcome));
  return {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"scene", scene_record(scene)},
      {"request",
       {{"all", true},
        {"period", request.period},
        {"phase_rad", request.phase},
        {"starts", request.starts},
        {"box", box},
        {"seed", request.seed},
        {"max_iterations", request.max_iterations},
        {"tolerance", request.tolerance},
        {"distinct_tolerance", request.distinct_tolerance},
        {"deflation",
         {{"enabled", request.deflate},
          {"power", Deflation{}.power},
          {"shift", Deflation{}.shift},
          {"radius", Deflation{}.radius},
          {"method", "deflated Newton shooting (Farrell, Birkisson & Funke 2015): "
                     "G(x) = M(x) (P^n(x) - x), M(x) = prod_i ((radius/|x - r_i|)^power + "
                     "shift) over every section point r_i of the orbits found before"}}}}},
      {"units", units},
      {"t_section", result.t_section},
      {"forcing_period", result.forcing_period},
      {"state_names", result.state_names},
      {"starts",
       {{"new_orbit", result.count(StartOutcome::new_orbit)},
        {"known_orbit", result.count(StartOutcome::known_orbit)},
        {"not_converged", result.count(StartOutcome::not_converged)},
        {"stopped", result.count(StartOutcome::stopped)},
        {"outcomes", outcomes},
        {"orbit", result.start_orbit}}},
      {"orbits", orbits},
  };
}

}  // namespace impactlab
