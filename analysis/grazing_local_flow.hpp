// The local data at a grazing point of a concrete system with Jacobians
// (GrazingLocalFlow, discontinuity_map.hpp), as the function that
// stroboscopic_map_problem.hpp gives its ContinuationProblem::grazing_flow:
// the virtual orbit (the touched wall's contacts suppressed in the window)
// run from the section state x to the touch at t since the section (Φ₁, one
// variational run) and from the touch on to the section one orbit later (Φ₂,
// a second run); at the touch the gap, its gradient and its rate's gradient
// (central differences of the witness rate, h = 1e-5 (1 + |x_i|)), the
// vector field and its Jacobian, the reset's Jacobian of an impact there (the
// system's on_event and reset_jacobian at a state moved off the touch to the
// normal speed 1e-6 of the gap's scale), and ḧ, h⃛ from the gap rate along
// the local trajectory (classical Runge–Kutta, 16 substeps of each step δ =
// max_step/20 from the touch, three either side; sixth-order central
// differences). The parameter derivatives are five-point central differences
// in p at fixed forcing phases (step 0.1 ε^{1/5} (1 + |p|), ε the scene's
// rtol, or 1e-15 for the exact flow): the state at the touch's phase and the
// image one orbit on, from the same section state, and the gap at the touch's
// state and phase.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <numbers>
#include <optional>
#include <string>

#include <impactlab/analysis/continuation_problem.hpp>
#include <impactlab/analysis/decorated_system.hpp>
#include <impactlab/analysis/discontinuity_map.hpp>
#include <impactlab/analysis/flow_setup.hpp>
#include <impactlab/analysis/map_evaluation.hpp>
#include <impactlab/analysis/variational.hpp>
#include <impactlab/simulate/flow.hpp>

namespace impactlab {

template <HasJacobian System, class MakeSystem, class OmegaOf>
std::function<GrazingLocalFlow(const OrbitPoint&, double, double, const ContactWindow&, double)>
grazing_local_flow_function(MakeSystem make_system, OmegaOf omega_of,
                            typename System::Mode flight_mode, const FlowSetup& setup,
                            int period) {
  using Wrapped = DecoratedSystem<System>;
  using Tangent = Variational<Wrapped>;
  using State = typename System::State;
  constexpr std::size_t n = tangent_dimension_of<System>;
  return [=](const OrbitPoint& x, double p, double section_phase, const ContactWindow& suppressed,
             double t_touch) {
    GrazingLocalFlow local;
    const auto fail = [&](const std::string& why) {
      local.completed = false;
      local.failure = why;
      return local;
    };
    const int k = suppressed.witness;
    if (k < 0 || x.size() < n) return fail("no wall to touch");
    const System system = make_system(p);
    const double omega = omega_of(system);
    const double t0 = section_phase / omega;
    const double span = period * 2.0 * std::numbers::pi / omega;
    local.time = t_touch;
    local.section_phase = section_phase;
    local.phase = section_phase + omega * t_touch;
    local.omega = omega;
    local.period = span;
    local.witness = k;
    const double touch_phase_offset = omega * t_touch;  // ψ_g − φ_s, held fixed as p moves

    // a run of the virtual orbit of `at` (its window shifted to absolute time)
    const auto window_at = [&](double start) {
      ContactWindow window = suppressed;
      window.from += start;
      window.to += start;
      return window;
    };
    State x0{};
    std::copy_n(x.begin(), n, x0.begin());
    const LoopOptions options = loop_options(setup);

    // Φ₁: the section to the touch; Φ₂: the touch to the section one orbit on
    const auto tangent_run = [&](const System& s, const State& from, double ta, double tb)
        -> std::optional<std::pair<State, MonodromyMatrix>> {
      const Wrapped wrapped = suppressing_contacts(s, flight_mode, window_at(t0), nullptr);
      const Tangent tangent(wrapped);
      EventLog log(false);
      const auto run = with_flow<Tangent>(setup.method, stepper_settings(tangent, setup),
                                          [&](auto& stepper) {
                                            return simulate(tangent, stepper,
                                                            tangent.start(from, flight_mode),
                                                            flight_mode, ta, tb, options, log);
                                          });
      if (run.termination != Termination::completed || run.mode != flight_mode ||
          run.counters.one_sided_events > 0)
        return std::nullopt;
      MonodromyMatrix phi;
      for (const auto& row : Tangent::fundamental_matrix(run.state))
        phi.emplace_back(row.begin(), row.end());
      return std::make_pair(Tangent::base_state(run.state), phi);
    };
    const auto first = tangent_run(system, x0, t0, t0 + t_touch);
    if (!first) return fail("the run to the touch did not complete");
    const State touch = first->first;
    local.to_touch = first->second;
    const auto second = tangent_run(system, touch, t0 + t_touch, t0 + span);
    if (!second) return fail("the run from the touch did not complete");
    local.from_touch = second->second;
    local.state.assign(touch.begin(), touch.begin() + n);

    // the gap and the field at the touch
    const double tg = t0 + t_touch;
    const auto kk = static_cast<std::size_t>(k);
    const WitnessSample h = system.witness(flight_mode, kk, touch, tg);
    local.gap = h.value;
    local.gap_rate = h.rate;
    const auto gradient = system.witness_gradient(flight_mode, kk, touch, tg);
    local.gap_gradient.assign(gradient.begin(), gradient.end());
    State f{};
    system.rhs(flight_mode, touch, f, tg);
    local.field.assign(f.begin(), f.begin() + n);
    TangentMatrixOf<n> jacobian{};
    system.jacobian(flight_mode, touch, tg, jacobian);
    for (const auto& row : jacobian) local.field_jacobian.emplace_back(row.begin(), row.end());
    local.rate_gradient.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const double step = 1e-5 * (1.0 + std::fabs(touch[i]));
      State up = touch, down = touch;
      up[i] += step;
      down[i] -= step;
      local.rate_gradient[i] = (system.witness(flight_mode, kk, up, tg).rate -
                                system.witness(flight_mode, kk, down, tg).rate) /
                               (2.0 * step);
    }

    // ḧ and h⃛ from the gap rate along the local trajectory (RK4, no events)
    const double delta = system.max_step() / 20.0;
    const auto rk4 = [&](State y, double t, double step, int substeps) {
      const double hstep = step / substeps;
      for (int s = 0; s < substeps; ++s) {
        State k1{}, k2{}, k3{}, k4{}, z{};
        system.rhs(flight_mode, y, k1, t);
        for (std::size_t i = 0; i < y.size(); ++i) z[i] = y[i] + 0.5 * hstep * k1[i];
        system.rhs(flight_mode, z, k2, t + 0.5 * hstep);
        for (std::size_t i = 0; i < y.size(); ++i) z[i] = y[i] + 0.5 * hstep * k2[i];
        system.rhs(flight_mode, z, k3, t + 0.5 * hstep);
        for (std::size_t i = 0; i < y.size(); ++i) z[i] = y[i] + hstep * k3[i];
        system.rhs(flight_mode, z, k4, t + hstep);
        for (std::size_t i = 0; i < y.size(); ++i)
          y[i] += hstep / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        t += hstep;
      }
      return y;
    };
    std::array<double, 7> rates{};
    rates[3] = h.rate;
    for (int side : {-1, 1}) {
      State y = touch;
      for (int j = 1; j <= 3; ++j) {
        y = rk4(y, tg + side * (j - 1) * delta, side * delta, 16);
        rates[3 + side * j] = system.witness(flight_mode, kk, y, tg + side * j * delta).rate;
      }
    }
    local.gap_acceleration = (-rates[0] + 9.0 * rates[1] - 45.0 * rates[2] + 45.0 * rates[4] -
                              9.0 * rates[5] + rates[6]) /
                             (60.0 * delta);
    local.gap_jerk = (2.0 * rates[0] - 27.0 * rates[1] + 270.0 * rates[2] - 490.0 * rates[3] +
                      270.0 * rates[4] - 27.0 * rates[5] + 2.0 * rates[6]) /
                     (180.0 * delta * delta);

    // the reset's Jacobian of an impact at the touch: the state moved along u
    // (∇h·u = 0, ∇ḣ·u = 1 for N = 2; the rate's gradient direction otherwise)
    // to a small approach speed, through on_event and reset_jacobian
    {
      double rate_norm = 0.0, along = 0.0;
      for (std::size_t i = 0; i < n; ++i) rate_norm += local.rate_gradient[i] * local.rate_gradient[i];
      for (std::size_t i = 0; i < n; ++i) along += local.rate_gradient[i] * local.gap_gradient[i];
      double gap_norm = 0.0;
      for (std::size_t i = 0; i < n; ++i) gap_norm += local.gap_gradient[i] * local.gap_gradient[i];
      // u ∝ ∇ḣ − (∇ḣ·∇h / |∇h|²) ∇h, scaled to ∇ḣ·u = 1
      std::array<double, n> u{};
      double u_rate = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        u[i] = local.rate_gradient[i] - (gap_norm > 0.0 ? along / gap_norm : 0.0) * local.gap_gradient[i];
        u_rate += local.rate_gradient[i] * u[i];
      }
      if (!(std::fabs(u_rate) > 0.0) || !(rate_norm > 0.0))
        return fail("the gap rate does not depend on the state at the touch");
      double scale = 0.0;
      for (std::size_t i = 0; i < n; ++i) scale = std::max(scale, std::fabs(touch[i]));
      const double speed = 1e-6 * (1.0 + scale);
      State approaching = touch;
      for (std::size_t i = 0; i < n; ++i) approaching[i] -= speed * u[i] / u_rate;
      EventLog log(false);
      const auto after =
          system.on_event(flight_mode, kk, CrossingKind::crossing, approaching, tg, log);
      if (after.stop || after.mode != flight_mode)
        return fail("an impact at the touch does not return to flight");
      const auto reset = system.reset_jacobian(flight_mode, kk, CrossingKind::crossing,
                                               approaching, tg, after);
      if (reset.collapses || reset.one_sided)
        return fail("an impact at the touch has no tangent map (it collapses or is one-sided)");
      for (const auto& row : reset.state) local.reset_jacobian.emplace_back(row.begin(), row.end());
    }

    // the parameter derivatives: five-point stencil at fixed forcing phases
    const double epsilon = setup.method == "exact" ? 1e-15 : std::max(setup.rtol, 1e-15);
    const double dp = 0.1 * std::pow(epsilon, 0.2) * (1.0 + std::fabs(p));
    local.parameter_step = dp;
    std::array<std::vector<double>, 4> touch_at, image_at;
    std::array<double, 4> gap_at{};
    const std::array<double, 4> offsets = {-2.0, -1.0, 1.0, 2.0};
    for (std::size_t j = 0; j < 4; ++j) {
      const double q = p + offsets[j] * dp;
      const System moved = make_system(q);
      const double w = omega_of(moved);
      const double start = section_phase / w;
      const double at_touch = start + touch_phase_offset / w;
      const double end = start + period * 2.0 * std::numbers::pi / w;
      const Wrapped wrapped = suppressing_contacts(moved, flight_mode, window_at(start), nullptr);
      EventLog log(false);
      const auto run_to = [&](const State& from, double ta, double tb) {
        return with_flow<Wrapped>(setup.method, stepper_settings(wrapped, setup),
                                  [&](auto& stepper) {
                                    return simulate(wrapped, stepper, from, flight_mode, ta, tb,
                                                    options, log);
                                  });
      };
      const auto to_touch = run_to(x0, start, at_touch);
      if (to_touch.termination != Termination::completed || to_touch.mode != flight_mode)
        return fail("a run at a moved parameter did not complete");
      const auto to_end = run_to(to_touch.state, at_touch, end);
      if (to_end.termination != Termination::completed || to_end.mode != flight_mode)
        return fail("a run at a moved parameter did not complete");
      touch_at[j].assign(to_touch.state.begin(), to_touch.state.begin() + n);
      image_at[j].assign(to_end.state.begin(), to_end.state.begin() + n);
      gap_at[j] = moved.witness(flight_mode, kk, touch, at_touch).value;
    }
    const auto stencil = [&](double a, double b, double c, double d) {
      return (a - 8.0 * b + 8.0 * c - d) / (12.0 * dp);
    };
    local.touch_parameter_derivative.assign(n, 0.0);
    local.image_parameter_derivative.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      local.touch_parameter_derivative[i] =
          stencil(touch_at[0][i], touch_at[1][i], touch_at[2][i], touch_at[3][i]);
      local.image_parameter_derivative[i] =
          stencil(image_at[0][i], image_at[1][i], image_at[2][i], image_at[3][i]);
    }
    local.gap_parameter_derivative = stencil(gap_at[0], gap_at[1], gap_at[2], gap_at[3]);
    local.completed = true;
    return local;
  };
}

}  // namespace impactlab
