// The local data at a grazing point of a concrete system with Jacobians
// (GrazingLocalFlow, discontinuity_map.hpp), as the function that
// stroboscopic_map_problem.hpp gives its ContinuationProblem::grazing_flow.
//
// The virtual orbit from the section state x at p, the located wall's
// contacts suppressed near the touch at t since the section, is sampled 192
// times an orbit for further touches: another wall (or the same one) whose
// gap has a local minimum within 1e-4 of its range of zero (a symmetric
// orbit between two walls touches both at once). Each is refined by Newton
// on the gap rate along the orbit and kept where its gap is below 1e-6 of
// that range. The orbit is then run from touch to touch, each leg in two
// halves that suppress the wall touched at their end (so that no touch is
// seen as a tiny impact): the states at the touches, and the flow from each
// touch to the next (the variational equations) and its parameter derivative
// (a five-point central difference in p at fixed forcing phases, step
// 0.1 ε^{1/5} (1 + |p|), ε the scene's rtol, or 1e-15 for the exact flow).
//
// At each touch: the gap and its rate, their gradients (the rate's by central
// differences, h = 1e-5 (1 + |x_i|)), the vector field's Jacobian, the reset's
// Jacobian of an impact there (the system's on_event and reset_jacobian at the
// state moved off the touch to the normal speed 1e-6 (1 + |x|)), ḧ and h⃛ from
// the gap rate along the local trajectory (classical Runge–Kutta, 16 substeps
// of each step δ = max_step/20, three steps either side, sixth-order central
// differences), and ∂h/∂p at the touch's state and phase.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

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
    const int located = suppressed.witness;
    if (located < 0 || x.size() < n) return fail("no wall to touch");
    const System system = make_system(p);
    const double omega = omega_of(system);
    const double span = period * 2.0 * std::numbers::pi / omega;
    local.section_phase = section_phase;
    local.omega = omega;
    local.period = span;
    const LoopOptions options = loop_options(setup);
    State x0{};
    std::copy_n(x.begin(), n, x0.begin());

    // A touch by its forcing phase (fixed as p moves) and wall.
    struct Touch {
      double phase;  // ωt, unreduced: section_phase + ω t since the section
      int witness;
    };
    const auto time_of = [](const Touch& touch, double w) { return touch.phase / w; };
    // the window of a touch at p's ω: a tenth of the orbit either side
    const auto window_of = [&](const Touch& touch, double w) {
      const double half = 0.1 * period * 2.0 * std::numbers::pi / w;
      return ContactWindow{touch.witness, time_of(touch, w) - half, time_of(touch, w) + half};
    };
    // a run of `s` from `from` over [ta, tb] with the window's wall suppressed
    const auto run = [&](const System& s, const State& from, double ta, double tb,
                         const ContactWindow& window) -> std::optional<State> {
      const Wrapped wrapped = suppressing_contacts(s, flight_mode, window, nullptr);
      EventLog log(false);
      const auto result = with_flow<Wrapped>(
          setup.method, stepper_settings(wrapped, setup), [&](auto& stepper) {
            return simulate(wrapped, stepper, from, flight_mode, ta, tb, options, log);
          });
      if (result.termination != Termination::completed || result.mode != flight_mode)
        return std::nullopt;
      return result.state;
    };
    const auto tangent_run = [&](const System& s, const State& from, double ta, double tb,
                                 const ContactWindow& window)
        -> std::optional<std::pair<State, MonodromyMatrix>> {
      const Wrapped wrapped = suppressing_contacts(s, flight_mode, window, nullptr);
      const Tangent tangent(wrapped);
      EventLog log(false);
      const auto result = with_flow<Tangent>(
          setup.method, stepper_settings(tangent, setup), [&](auto& stepper) {
            return simulate(tangent, stepper, tangent.start(from, flight_mode), flight_mode, ta, tb,
                            options, log);
          });
      if (result.termination != Termination::completed || result.mode != flight_mode ||
          result.counters.one_sided_events > 0)
        return std::nullopt;
      MonodromyMatrix phi;
      for (const auto& row : Tangent::fundamental_matrix(result.state))
        phi.emplace_back(row.begin(), row.end());
      return std::make_pair(Tangent::base_state(result.state), phi);
    };
    // a leg from `ta` to `tb` in two halves, the first suppressing the wall of
    // `a` near its time, the second that of `b`; tangent: with the flow's
    // Jacobian
    const auto leg = [&](const System& s, const State& from, double ta, double tb,
                         const Touch& a, const Touch& b,
                         bool tangent) -> std::optional<std::pair<State, MonodromyMatrix>> {
      const double w = omega_of(s);
      const double mid = 0.5 * (ta + tb);
      if (!tangent) {
        const auto half = run(s, from, ta, mid, window_of(a, w));
        if (!half) return std::nullopt;
        const auto end = run(s, *half, mid, tb, window_of(b, w));
        if (!end) return std::nullopt;
        return std::make_pair(*end, MonodromyMatrix{});
      }
      const auto first = tangent_run(s, from, ta, mid, window_of(a, w));
      if (!first) return std::nullopt;
      const auto second = tangent_run(s, first->first, mid, tb, window_of(b, w));
      if (!second) return std::nullopt;
      MonodromyMatrix product(n, std::vector<double>(n, 0.0));
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
          for (std::size_t k = 0; k < n; ++k)
            product[i][j] += second->second[i][k] * first->second[k][j];
      return std::make_pair(second->first, product);
    };

    // the gap rate's derivatives along the local trajectory (RK4, no events)
    const double delta = system.max_step() / 20.0;
    const auto rk4 = [&](State y, double t, double step) {
      constexpr int substeps = 16;
      const double h = step / substeps;
      for (int s = 0; s < substeps; ++s) {
        State k1{}, k2{}, k3{}, k4{}, z{};
        system.rhs(flight_mode, y, k1, t);
        for (std::size_t i = 0; i < y.size(); ++i) z[i] = y[i] + 0.5 * h * k1[i];
        system.rhs(flight_mode, z, k2, t + 0.5 * h);
        for (std::size_t i = 0; i < y.size(); ++i) z[i] = y[i] + 0.5 * h * k2[i];
        system.rhs(flight_mode, z, k3, t + 0.5 * h);
        for (std::size_t i = 0; i < y.size(); ++i) z[i] = y[i] + h * k3[i];
        system.rhs(flight_mode, z, k4, t + h);
        for (std::size_t i = 0; i < y.size(); ++i)
          y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        t += h;
      }
      return y;
    };
    // ḣ at t + jδ, j = −3 … 3, of the trajectory through y at t
    const auto rates_around = [&](const State& y, double t, std::size_t witness) {
      std::array<double, 7> rates{};
      rates[3] = system.witness(flight_mode, witness, y, t).rate;
      for (int side : {-1, 1}) {
        State z = y;
        for (int j = 1; j <= 3; ++j) {
          z = rk4(z, t + side * (j - 1) * delta, side * delta);
          rates[3 + side * j] = system.witness(flight_mode, witness, z, t + side * j * delta).rate;
        }
      }
      return rates;
    };
    const auto acceleration = [&](const std::array<double, 7>& r) {
      return (-r[0] + 9.0 * r[1] - 45.0 * r[2] + 45.0 * r[4] - 9.0 * r[5] + r[6]) / (60.0 * delta);
    };
    const auto jerk = [&](const std::array<double, 7>& r) {
      return (2.0 * r[0] - 27.0 * r[1] + 270.0 * r[2] - 490.0 * r[3] + 270.0 * r[4] -
              27.0 * r[5] + 2.0 * r[6]) /
             (180.0 * delta * delta);
    };

    // the touches: the located one, then further ones from samples of the
    // virtual orbit (the located wall suppressed near its touch)
    std::vector<Touch> touches = {{section_phase + omega * t_touch, located}};
    const double t0 = section_phase / omega;
    {
      const ContactWindow first_window = window_of(touches[0], omega);
      const int count = 192 * period;
      GapSampler<System> sampler(system, flight_mode, t0, span / count, count - 1);
      const Wrapped wrapped = suppressing_contacts(system, flight_mode, first_window, nullptr);
      EventLog log(false);
      const auto sampled = with_flow<Wrapped>(
          setup.method, stepper_settings(wrapped, setup), [&](auto& stepper) {
            return simulate(wrapped, stepper, x0, flight_mode, t0, t0 + span, options, log,
                            sampler);
          });
      if (sampled.termination != Termination::completed)
        return fail("the virtual orbit's run did not complete");
      const auto& samples = sampler.samples;
      for (std::size_t k = 0; k < System::max_witnesses; ++k) {
        double range = 0.0;
        for (const auto& sample : samples)
          if (sample.flight && std::isfinite(sample.gap[k]))
            range = std::max(range, std::fabs(sample.gap[k]));
        for (std::size_t j = 1; j + 1 < samples.size(); ++j) {
          if (!samples[j - 1].flight || !samples[j].flight || !samples[j + 1].flight) continue;
          const double a = samples[j - 1].gap[k], b = samples[j].gap[k], c = samples[j + 1].gap[k];
          if (!(b <= a && b < c) || !std::isfinite(a + b + c)) continue;
          const double curvature = a - 2.0 * b + c;
          const double offset = curvature > 0.0 ? 0.5 * (a - c) / curvature : 0.0;
          const double lowest = b - 0.125 * (a - c) * offset;
          if (!(std::fabs(lowest) <= 1e-4 * range)) continue;
          double t = samples[j].t + offset * (samples[j + 1].t - samples[j].t);
          // the located touch itself
          if (static_cast<int>(k) == located &&
              std::fabs(std::remainder(t - (t0 + t_touch), span)) < 0.1 * span)
            continue;
          // Newton on the gap rate along the orbit
          for (int iteration = 0; iteration < 4; ++iteration) {
            const auto there = run(system, x0, t0, t, window_of(touches[0], omega));
            if (!there) break;
            const auto rates = rates_around(*there, t, k);
            const double accel = acceleration(rates);
            if (!(accel > 0.0)) break;
            const double step = -rates[3] / accel;
            const double gap = system.witness(flight_mode, k, *there, t).value;
            if (std::fabs(step) < 1e-9 * span && std::fabs(gap) <= 1e-6 * range) {
              touches.push_back({omega * t, static_cast<int>(k)});
              break;
            }
            t += step;
          }
        }
      }
    }
    // in their order along the orbit from the located one
    const double first_phase = touches[0].phase;
    std::sort(touches.begin() + 1, touches.end(), [&](const Touch& a, const Touch& b) {
      const double full = 2.0 * std::numbers::pi * period;
      const auto after = [&](const Touch& t) {
        const double d = std::fmod(t.phase - first_phase, full);
        return d < 0.0 ? d + full : d;
      };
      return after(a) < after(b);
    });
    // each further touch's phase after the first's, within one orbit
    for (std::size_t j = 1; j < touches.size(); ++j) {
      const double full = 2.0 * std::numbers::pi * period;
      double d = std::fmod(touches[j].phase - first_phase, full);
      if (d < 0.0) d += full;
      touches[j].phase = first_phase + d;
    }
    const std::size_t count = touches.size();
    // the touch after j (the last's: the first, one orbit on)
    const auto next_of = [&](std::size_t j) {
      if (j + 1 < count) return touches[j + 1];
      Touch again = touches[0];
      again.phase += 2.0 * std::numbers::pi * period;
      return again;
    };

    // the state at the located touch, from the section (the window of the
    // touch before it, an orbit earlier, where that lies near the section)
    std::vector<State> states(count);
    {
      Touch before = touches[count - 1];
      before.phase -= 2.0 * std::numbers::pi * period;
      const auto at =
          leg(system, x0, t0, time_of(touches[0], omega), before, touches[0], false);
      if (!at) return fail("the run to the touch did not complete");
      states[0] = at->first;
    }
    // the segments, touch to touch, and the states on the way
    for (std::size_t j = 0; j < count; ++j) {
      const Touch next = next_of(j);
      const auto segment = leg(system, states[j], time_of(touches[j], omega),
                               time_of(next, omega), touches[j], next, true);
      if (!segment) return fail("the run between touches did not complete");
      if (j + 1 < count) states[j + 1] = segment->first;
      local.segments.push_back({segment->second, {}});
    }

    // each touch's geometry
    for (std::size_t j = 0; j < count; ++j) {
      const State& xt = states[j];
      const double t = time_of(touches[j], omega);
      const auto k = static_cast<std::size_t>(touches[j].witness);
      GrazingTouch touch;
      touch.witness = touches[j].witness;
      touch.time = t - t0;
      touch.phase = touches[j].phase;
      touch.state.assign(xt.begin(), xt.begin() + n);
      const WitnessSample h = system.witness(flight_mode, k, xt, t);
      touch.gap = h.value;
      touch.gap_rate = h.rate;
      const auto gradient = system.witness_gradient(flight_mode, k, xt, t);
      touch.gap_gradient.assign(gradient.begin(), gradient.end());
      TangentMatrixOf<n> jacobian{};
      system.jacobian(flight_mode, xt, t, jacobian);
      for (const auto& row : jacobian) touch.field_jacobian.emplace_back(row.begin(), row.end());
      touch.rate_gradient.assign(n, 0.0);
      for (std::size_t i = 0; i < n; ++i) {
        const double step = 1e-5 * (1.0 + std::fabs(xt[i]));
        State up = xt, down = xt;
        up[i] += step;
        down[i] -= step;
        touch.rate_gradient[i] = (system.witness(flight_mode, k, up, t).rate -
                                  system.witness(flight_mode, k, down, t).rate) /
                                 (2.0 * step);
      }
      const auto rates = rates_around(xt, t, k);
      touch.gap_acceleration = acceleration(rates);
      touch.gap_jerk = jerk(rates);

      // the reset's Jacobian of an impact at the touch: the state moved along
      // u ∝ ∇ḣ − (∇ḣ·∇h/|∇h|²)∇h (∇h·u = 0) to the approach speed 1e-6 (1 + |x|)
      double gap_norm = 0.0, along = 0.0, scale = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        gap_norm += touch.gap_gradient[i] * touch.gap_gradient[i];
        along += touch.rate_gradient[i] * touch.gap_gradient[i];
        scale = std::max(scale, std::fabs(xt[i]));
      }
      std::array<double, n> u{};
      double u_rate = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        u[i] = touch.rate_gradient[i] -
               (gap_norm > 0.0 ? along / gap_norm : 0.0) * touch.gap_gradient[i];
        u_rate += touch.rate_gradient[i] * u[i];
      }
      if (!(u_rate > 0.0)) return fail("the gap rate does not depend on the state at a touch");
      const double speed = 1e-6 * (1.0 + scale);
      State approaching = xt;
      for (std::size_t i = 0; i < n; ++i) approaching[i] -= speed * u[i] / u_rate;
      EventLog log(false);
      const auto after =
          system.on_event(flight_mode, k, CrossingKind::crossing, approaching, t, log);
      if (after.stop || after.mode != flight_mode)
        return fail("an impact at a touch does not return to flight");
      const auto reset =
          system.reset_jacobian(flight_mode, k, CrossingKind::crossing, approaching, t, after);
      if (reset.collapses || reset.one_sided)
        return fail("an impact at a touch has no tangent map (it collapses or is one-sided)");
      for (const auto& row : reset.state) touch.reset_jacobian.emplace_back(row.begin(), row.end());
      local.touches.push_back(std::move(touch));
    }

    // the parameter derivatives: five-point stencil at fixed forcing phases
    const double epsilon = setup.method == "exact" ? 1e-15 : std::max(setup.rtol, 1e-15);
    const double dp = 0.1 * std::pow(epsilon, 0.2) * (1.0 + std::fabs(p));
    local.parameter_step = dp;
    const std::array<double, 4> offsets = {-2.0, -1.0, 1.0, 2.0};
    const auto stencil = [&](const std::array<double, 4>& f) {
      return (f[0] - 8.0 * f[1] + 8.0 * f[2] - f[3]) / (12.0 * dp);
    };
    std::vector<std::array<std::array<double, 4>, n>> ends(count);
    std::vector<std::array<double, 4>> gaps(count);
    for (std::size_t m = 0; m < 4; ++m) {
      const System moved = make_system(p + offsets[m] * dp);
      const double w = omega_of(moved);
      for (std::size_t j = 0; j < count; ++j) {
        const Touch next = next_of(j);
        const auto segment = leg(moved, states[j], time_of(touches[j], w), time_of(next, w),
                                 touches[j], next, false);
        if (!segment) return fail("a run at a moved parameter did not complete");
        for (std::size_t i = 0; i < n; ++i) ends[j][i][m] = segment->first[i];
        gaps[j][m] = moved
                         .witness(flight_mode, static_cast<std::size_t>(touches[j].witness),
                                  states[j], time_of(touches[j], w))
                         .value;
      }
    }
    for (std::size_t j = 0; j < count; ++j) {
      local.segments[j].parameter_derivative.assign(n, 0.0);
      for (std::size_t i = 0; i < n; ++i)
        local.segments[j].parameter_derivative[i] = stencil(ends[j][i]);
      local.touches[j].gap_parameter_derivative = stencil(gaps[j]);
    }
    local.completed = true;
    return local;
  };
}

}  // namespace impactlab
