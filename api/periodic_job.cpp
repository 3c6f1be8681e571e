#include <impactlab/api/periodic_job.hpp>

#include <chrono>
#include <cstdlib>

#include <impactlab/analysis/sweep.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/scene_record.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace {

nlohmann::json complex_record(std::complex<double> z) {
  return {{"re", z.real()}, {"im", z.imag()}, {"abs", std::abs(z)}};
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
    char* end = nullptr;
    const long n = std::strtol(job.period.c_str(), &end, 10);
    if (end == job.period.c_str() || *end != '\0' || n < 1 || n > 1000)
      throw BadInput("period", job.period, "expected auto or a whole number from 1 to 1000");
    request.period = static_cast<int>(n);
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

}  // namespace impactlab
