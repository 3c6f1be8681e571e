// An impact oscillator defined outside impactlab (two_stop_oscillator.hpp),
// run through the installed library: the event loop, Poincaré sections,
// Newton shooting with Floquet multipliers, and a sweep over ω. Two
// closed-form facts are checked, so that the program fails loudly when the
// library or the oscillator is wrong:
//   1. between impacts the event loop follows the closed-form solution of
//      ẍ + 2ζẋ + x = A cos ωt, and each impact gives ẋ⁺ = −r ẋ⁻;
//   2. the product of the Floquet multipliers of an orbit of period T with n
//      impacts is r^(2n) e^(−2ζT): the flow contracts areas by e^(−2ζT)
//      (Liouville) and each impact's saltation matrix has determinant r².
// Exit status: 0 when every check holds, 1 when one fails, 2 for bad input.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include <impactlab/analysis/run_periodic.hpp>
#include <impactlab/analysis/run_section.hpp>
#include <impactlab/analysis/sweep.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/scene.hpp>
#include "two_stop_oscillator.hpp"

#include <impactlab/analysis/analysis_flows.hpp>

// the flows the analyses below run for the oscillator: the event loop bound
// to every stepper, compiled here once (analysis/analysis_flows.hpp)
IMPACTLAB_TANGENT_FLOW_ENGINES(two_stop::TwoStopOscillator);

namespace {

using impactlab::BadInput;
using impactlab::Scene;
using impactlab::SceneSchema;
using two_stop::TwoStopOscillator;

// --- the scene binding: schema, system, section hook -------------------------

const SceneSchema& schema() {
  static const SceneSchema instance = [] {
    SceneSchema built{"two_stop", "x", impactlab::common_keys()};
    const double inf = 1e308;
    const std::vector<impactlab::KeySpec> own = {
        {.key = "zeta", .help = "damping ratio", .default_number = 0.05, .lower = 0.0,
         .upper = inf},
        {.key = "A", .unit = "length", .help = "forcing amplitude", .default_number = 1.0,
         .lower = -inf, .upper = inf},
        {.key = "omega", .help = "forcing frequency over the natural frequency",
         .default_number = 2.0, .lower = 0.0, .upper = inf, .lower_open = true},
        {.key = "gap", .unit = "length", .help = "half the distance between the stops",
         .default_number = 0.25, .lower = 0.0, .upper = inf, .lower_open = true},
        {.key = "r", .help = "coefficient of restitution", .default_number = 0.8, .lower = 0.0,
         .upper = 1.0},
        {.key = "initial.x", .unit = "length", .help = "initial position, |x| <= gap",
         .default_number = 0.0, .lower = -inf, .upper = inf},
        {.key = "initial.x_dot", .unit = "length/time", .help = "initial velocity",
         .default_number = 0.0, .lower = -inf, .upper = inf},
    };
    built.keys.insert(built.keys.end(), own.begin(), own.end());
    return built;
  }();
  return instance;
}

TwoStopOscillator make_system(const Scene& scene) {
  if (scene.text("integrator.method") == "exact")
    throw BadInput("integrator.method", "exact", "two_stop has no closed-form flow");
  return TwoStopOscillator({.zeta = scene.number("zeta"),
                            .A = scene.number("A"),
                            .omega = scene.number("omega"),
                            .gap = scene.number("gap"),
                            .r = scene.number("r")});
}

TwoStopOscillator::State initial_state(const Scene& scene) {
  const double x = scene.number("initial.x");
  if (std::fabs(x) > scene.number("gap"))
    throw BadInput("initial.x", impactlab::to_text(x), "starts beyond a stop");
  return {x, scene.number("initial.x_dot")};
}

// The Poincaré-section hook a sweep calls (impactlab::SweepTarget::section).
impactlab::SectionResult section(const Scene& scene, const impactlab::SectionRequest& request) {
  const TwoStopOscillator system = make_system(scene);
  const double gap = system.parameters().gap;
  // a state continued from the previous sweep value stays between the stops
  auto admissible = [gap](TwoStopOscillator::State& x, TwoStopOscillator::Mode&) {
    x[0] = std::clamp(x[0], -gap, gap);
  };
  return impactlab::run_section(system, initial_state(scene), TwoStopOscillator::Mode::free, scene,
                                request, system.parameters().omega, admissible);
}

// --- independent closed-form reference ---------------------------------------

// x(t), ẋ(t) of ẍ + 2ζẋ + x = A cos ωt (ζ < 1) from x(t0) = x0, ẋ(t0) = v0:
// x = e^{−ζτ}(c₁ cos ω_d τ + c₂ sin ω_d τ) + P cos ωt + Q sin ωt, τ = t − t0.
std::array<double, 2> free_flight(const two_stop::Parameters& p, double t0, double x0, double v0,
                                  double t) {
  const double detuning = 1.0 - p.omega * p.omega;
  const double denominator = detuning * detuning + 4.0 * p.zeta * p.zeta * p.omega * p.omega;
  const double P = p.A * detuning / denominator;
  const double Q = 2.0 * p.zeta * p.omega * p.A / denominator;
  auto particular = [&](double s) {
    return std::array<double, 2>{P * std::cos(p.omega * s) + Q * std::sin(p.omega * s),
                                 p.omega * (Q * std::cos(p.omega * s) - P * std::sin(p.omega * s))};
  };
  const double omega_d = std::sqrt(1.0 - p.zeta * p.zeta);
  const auto [xp0, vp0] = particular(t0);
  const double c1 = x0 - xp0;
  const double c2 = (v0 - vp0 + p.zeta * c1) / omega_d;
  const double tau = t - t0;
  const double decay = std::exp(-p.zeta * tau);
  const double c = std::cos(omega_d * tau), s = std::sin(omega_d * tau);
  const auto [xp, vp] = particular(t);
  return {decay * (c1 * c + c2 * s) + xp,
          decay * ((omega_d * c2 - p.zeta * c1) * c - (omega_d * c1 + p.zeta * c2) * s) + vp};
}

int failures = 0;

void check(bool holds, const std::string& what) {
  std::printf("  [%s] %s\n", holds ? "ok" : "FAILED", what.c_str());
  if (!holds) {
    std::fprintf(stderr, "custom_oscillator: check failed: %s\n", what.c_str());
    ++failures;
  }
}

// --- 1. the event loop against the closed form --------------------------------

void event_loop(const Scene& scene) {
  const TwoStopOscillator system = make_system(scene);
  const two_stop::Parameters& p = system.parameters();
  const impactlab::FlowSetup setup = impactlab::flow_setup(scene);
  const double period = 2.0 * std::numbers::pi / p.omega;
  const double t0 = scene.number("t0");
  const TwoStopOscillator::State x0 = initial_state(scene);
  impactlab::EventLog log;
  const auto run = impactlab::with_stepper<TwoStopOscillator>(
      setup.method, impactlab::stepper_settings(system, setup), [&](auto& stepper) {
        return impactlab::simulate(system, stepper, x0, TwoStopOscillator::Mode::free, t0,
                                   t0 + 10.0 * period, impactlab::loop_options(setup), log);
      });
  std::printf("event loop: 10 forcing periods, %s, %llu steps, %llu impacts\n",
              std::string(impactlab::to_string(run.termination)).c_str(),
              static_cast<unsigned long long>(run.counters.steps),
              static_cast<unsigned long long>(log.count(impactlab::EventKind::impact)));

  // every flight, from the state after one impact to the next impact
  double t = t0, x = x0[0], v = x0[1];
  double worst_position = 0.0, worst_velocity = 0.0, worst_ratio = 0.0;
  int walls_hit[2] = {0, 0};
  for (const auto& event : log.records()) {
    if (event.kind != impactlab::EventKind::impact) continue;
    const auto [x_closed, v_closed] = free_flight(p, t, x, v, event.t);
    worst_position = std::max(worst_position, std::fabs(x_closed - event.wall * p.gap));
    worst_velocity = std::max(worst_velocity, std::fabs(v_closed - event.qdot_before));
    worst_ratio = std::max(worst_ratio, std::fabs(event.qdot_after / event.qdot_before + p.r));
    ++walls_hit[event.wall > 0 ? 0 : 1];
    t = event.t;
    x = event.q;
    v = event.qdot_after;
  }
  const auto [x_end, v_end] = free_flight(p, t, x, v, run.t);
  worst_position = std::max(worst_position, std::fabs(x_end - run.state[0]));
  worst_velocity = std::max(worst_velocity, std::fabs(v_end - run.state[1]));
  std::printf("  impacts on +d: %d, on -d: %d; largest error against the closed form: "
              "x %.2e, x_dot %.2e\n", walls_hit[0], walls_hit[1], worst_position, worst_velocity);
  check(run.termination == impactlab::Termination::completed, "the run completes");
  check(walls_hit[0] >= 5 && walls_hit[1] >= 5, "both stops are hit, at least 5 times each");
  check(worst_position < 1e-8 && worst_velocity < 1e-8,
        "every free flight matches the closed-form solution to 1e-8");
  check(worst_ratio < 1e-14, "every impact gives x_dot+ = -r x_dot-");
}

// --- 2. Poincaré sections and 3. Floquet multipliers --------------------------

void section_and_floquet(const Scene& scene) {
  impactlab::SectionRequest request;
  request.transient_periods = 200.0;
  request.points = 8;
  request.section = impactlab::parse_section("strobe", "section");
  const impactlab::SectionResult strobe = section(scene, request);
  std::printf("stroboscopic section (phase 0), after %g periods:\n", request.transient_periods);
  for (const auto& point : strobe.points)
    std::printf("  t = %9.4f  x = %+.10f  x_dot = %+.10f\n", point.t, point.q, point.qdot);
  const double impacts_per_period = static_cast<double>(strobe.impacts) / strobe.periods_recorded;
  std::printf("  %g impacts per forcing period\n", impacts_per_period);

  request.section = impactlab::parse_section("impact:1", "section");
  request.points = 4;
  const impactlab::SectionResult impact_map = section(scene, request);
  std::printf("impact map on the stop +d (velocity just before each impact):\n");
  for (const auto& point : impact_map.points)
    std::printf("  t = %9.4f  x_dot- = %+.10f\n", point.t, point.qdot);

  const TwoStopOscillator system = make_system(scene);
  const two_stop::Parameters& p = system.parameters();
  const impactlab::PeriodicResult orbit =
      impactlab::run_periodic(system, initial_state(scene), TwoStopOscillator::Mode::free, scene,
                              impactlab::PeriodicRequest{}, p.omega);
  const auto& m = orbit.monodromy;
  const double determinant = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  const double impacts = std::round(impacts_per_period);
  const double expected =
      std::pow(p.r, 2.0 * impacts) * std::exp(-2.0 * p.zeta * orbit.orbit_period);
  std::printf("period-1 orbit by Newton shooting: x = %+.10f, x_dot = %+.10f (%d iterations)\n",
              orbit.state.empty() ? NAN : orbit.state[0],
              orbit.state.size() < 2 ? NAN : orbit.state[1], orbit.iterations);
  std::printf("  Floquet multipliers %+.6f%+.6fi, %+.6f%+.6fi; product %.10f, "
              "r^(2n) e^(-2 zeta T) = %.10f\n",
              orbit.multipliers[0].real(), orbit.multipliers[0].imag(),
              orbit.multipliers[1].real(), orbit.multipliers[1].imag(), determinant, expected);
  check(orbit.converged, "Newton shooting converges to the period-1 orbit");
  check(std::fabs(determinant - expected) < 1e-6 * expected,
        "the multipliers' product equals r^(2n) e^(-2 zeta T) to 1e-6");
  check(std::abs(orbit.multipliers[0]) < 1.0 && std::abs(orbit.multipliers[1]) < 1.0,
        "the orbit is stable (both multipliers inside the unit circle)");
}

// --- 4. a sweep over ω, through the library's sweep with this oscillator's hook

void sweep(const Scene& scene) {
  impactlab::SweepPlan plan;
  plan.axes = {impactlab::SweepAxis{.name = "omega", .from = 1.6, .to = 2.4, .count = 9}};
  plan.section.transient_periods = 200.0;
  plan.section.points = 16;
  impactlab::validate_plan(plan, scene, schema());
  const impactlab::SweepTarget target{&schema(), &section};
  std::printf("sweep over omega (each value continues from the previous one):\n"
              "  omega   period  impacts/period  termination\n");
  int completed = 0, points = 0;
  for (const auto& task : impactlab::sweep_tasks(plan)) {
    const auto records = impactlab::run_sweep_task(
        scene, target, plan, task, [](int) { return nullptr; },
        [](const impactlab::SweepRecord&) {}, [] { return true; });
    for (const auto& record : records) {
      std::printf("  %.3f  %6d  %14g  %s\n", plan.axes[0].value(record.index[0]),
                  record.classification.period, record.classification.impacts_per_period,
                  std::string(impactlab::to_string(record.result.termination)).c_str());
      completed += record.result.termination == impactlab::SectionTermination::completed;
      ++points;
    }
  }
  check(points == 9 && completed == points, "every sweep point runs to completion");
}

}  // namespace

int main() {
  try {
    const Scene scene = impactlab::read_scene(
        TWO_STOP_SCENE, [](std::string_view oscillator) -> const SceneSchema& {
          if (oscillator != schema().oscillator)
            throw BadInput("oscillator", std::string(oscillator), "this program knows two_stop only");
          return schema();
        });
    std::printf("scene %s: zeta = %g, A = %g, omega = %g, gap = %g, r = %g\n",
                scene.name.c_str(), scene.number("zeta"), scene.number("A"),
                scene.number("omega"), scene.number("gap"), scene.number("r"));
    event_loop(scene);
    section_and_floquet(scene);
    sweep(scene);
  } catch (const BadInput& error) {
    std::fprintf(stderr, "custom_oscillator: %s\n", error.what());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "custom_oscillator: %s\n", error.what());
    return 1;
  }
  if (failures > 0) {
    std::fprintf(stderr, "custom_oscillator: %d check(s) failed\n", failures);
    return 1;
  }
  std::printf("all checks hold\n");
  return 0;
}
