// The section map of a concrete system with Jacobians as a ContinuationProblem
// (analysis/continuation.hpp): Pⁿ(x; p) from the section ωt ≡ phase, its
// saltation-corrected monodromy, the impact signature, the slowest impact and
// the lowest flight gap (sampled), and the gap along the orbit with one
// wall's contacts suppressed near a time (the virtual orbit of a grazing
// point's extended system).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "analysis/continuation.hpp"
#include "analysis/curve_continuation.hpp"
#include "analysis/flow_setup.hpp"
#include "analysis/variational.hpp"
#include "core/simulator.hpp"
#include "integrate/stepper_dispatch.hpp"
#include "io/bad_input.hpp"
#include "io/scene.hpp"

namespace impactlab {

// What the wrapper saw of the crossings during one run.
struct CrossingTrace {
  struct Crossing {
    double t;      // s
    int witness;
    double speed;  // |witness rate| just before (the normal approach speed)
  };
  std::vector<Crossing> crossings;
};

// The forcing frequency of a system (rad/s): parameters().omega of the
// built-in oscillators, forcing_frequency() of a model file's.
template <class System>
double forcing_omega_of(const System& system) {
  if constexpr (requires { system.forcing_frequency(); })
    return system.forcing_frequency();
  else
    return system.parameters().omega;
}

template <class Base>
constexpr bool affine_flow_of() {
  if constexpr (requires { Base::affine_flow; }) return Base::affine_flow;
  return false;
}

// A system whose witness `window.witness` does not fire in flight mode between
// the absolute times window.from and window.to (it reads +1 there), and that
// notes every crossing it is told of.
template <HasJacobian Base>
class SuppressedContacts {
 public:
  using State = typename Base::State;
  using Mode = typename Base::Mode;
  static constexpr std::size_t max_witnesses = Base::max_witnesses;
  static constexpr bool affine_flow = affine_flow_of<Base>();
  static constexpr std::size_t tangent_dimension = tangent_dimension_of<Base>;

  SuppressedContacts(const Base& base, Mode flight_mode, ContactWindow window, CrossingTrace* trace)
      : base_(base), flight_mode_(flight_mode), window_(window), trace_(trace) {}

  [[nodiscard]] double max_step() const { return base_.max_step(); }
  void rhs(Mode mode, const State& x, State& dxdt, double t) const { base_.rhs(mode, x, dxdt, t); }
  [[nodiscard]] std::size_t witness_count(Mode mode) const { return base_.witness_count(mode); }
  [[nodiscard]] TriggerDirection trigger_direction(Mode mode, std::size_t k) const {
    return base_.trigger_direction(mode, k);
  }
  [[nodiscard]] bool suppressed(Mode mode, std::size_t k, double t) const {
    return mode == flight_mode_ && static_cast<int>(k) == window_.witness && t >= window_.from &&
           t <= window_.to;
  }
  [[nodiscard]] WitnessSample witness(Mode mode, std::size_t k, const State& x, double t) const {
    if (suppressed(mode, k, t)) return {1.0, 0.0};
    return base_.witness(mode, k, x, t);
  }
  Transition<State, Mode> on_event(Mode mode, std::size_t k, CrossingKind crossing, const State& x,
                                   double t, EventLog& log) const {
    if (trace_ && crossing == CrossingKind::crossing && mode == flight_mode_)
      trace_->crossings.push_back(
          {t, static_cast<int>(k), std::fabs(base_.witness(mode, k, x, t).rate)});
    return base_.on_event(mode, k, crossing, x, t, log);
  }
  void exact_flow(Mode mode, const State& x0, double t0, double t, State& x) const
    requires HasExactFlow<Base>
  {
    base_.exact_flow(mode, x0, t0, t, x);
  }
  void jacobian(Mode mode, const State& x, double t, TangentMatrixOf<tangent_dimension>& j) const {
    base_.jacobian(mode, x, t, j);
  }
  [[nodiscard]] TangentVectorOf<tangent_dimension> witness_gradient(Mode mode, std::size_t k,
                                                                    const State& x,
                                                                    double t) const {
    if (suppressed(mode, k, t)) return {};
    return base_.witness_gradient(mode, k, x, t);
  }
  [[nodiscard]] ResetJacobianOf<tangent_dimension> reset_jacobian(
      Mode mode, std::size_t k, CrossingKind crossing, const State& x, double t,
      const Transition<State, Mode>& after) const {
    return base_.reset_jacobian(mode, k, crossing, x, t, after);
  }
  [[nodiscard]] bool pinned(Mode mode) const { return base_.pinned(mode); }

 private:
  Base base_;
  Mode flight_mode_;
  ContactWindow window_;
  CrossingTrace* trace_;
};

// Samples of the wall gaps in flight, for the lowest flight gap.
template <class Base>
class GapSampler {
 public:
  using Mode = typename Base::Mode;
  GapSampler(const Base& base, Mode flight_mode, double t0, double spacing, int count)
      : base_(base), flight_mode_(flight_mode), t0_(t0), spacing_(spacing), count_(count) {}
  [[nodiscard]] double next_time() const {
    return next_ < count_ ? t0_ + (next_ + 1) * spacing_ : INFINITY;
  }
  template <class State>
  void observe(double t, const State& v, Mode mode) {
    ++next_;
    typename Base::State x;
    std::copy_n(v.begin(), x.size(), x.begin());
    Sample sample{t, mode == flight_mode_, {}};
    for (std::size_t k = 0; k < Base::max_witnesses; ++k)
      sample.gap[k] = k < base_.witness_count(mode) ? base_.witness(mode, k, x, t).value : INFINITY;
    samples.push_back(sample);
  }
  struct Sample {
    double t;
    bool flight;
    std::array<double, Base::max_witnesses> gap;
  };
  std::vector<Sample> samples;

 private:
  const Base& base_;
  Mode flight_mode_;
  double t0_, spacing_;
  int count_, next_ = 0;
};

// The problem for p ↦ make_system(p) (forcing_omega_of gives its forcing
// frequency), section ωt ≡ phase, period n, from flight mode.
template <HasJacobian System, class MakeSystem>
ContinuationProblem section_map_problem(MakeSystem make_system, typename System::Mode flight_mode,
                                        const FlowSetup& setup, double phase, int period,
                                        double forcing_omega_at_start) {
  using Mode = typename System::Mode;
  using Wrapped = SuppressedContacts<System>;
  using Tangent = Variational<Wrapped>;
  constexpr std::size_t n = tangent_dimension_of<System>;  // the OrbitPoint's components
  constexpr int samples_per_period = 96;
  struct Shared {
    MakeSystem make_system;
    Mode flight_mode;
    FlowSetup setup;
    double phase;
    int period;
  };
  auto shared = std::make_shared<Shared>(Shared{make_system, flight_mode, setup, phase, period});

  ContinuationProblem problem;
  problem.forcing_period_at_p = period * 2.0 * std::numbers::pi / forcing_omega_at_start;
  problem.phase = phase;
  problem.dimension = n;
  problem.evaluate = [shared](const OrbitPoint& x, double p, double section_phase, bool detailed,
                              const ContactWindow& suppressed) {
    OrbitEvaluation result;
    const System system = shared->make_system(p);
    const double omega = forcing_omega_of(system);
    const double t0 = section_phase / omega;
    const double span = shared->period * 2.0 * std::numbers::pi / omega;
    CrossingTrace trace;
    ContactWindow window = suppressed;
    window.from += t0;
    window.to += t0;
    const Wrapped wrapped(system, shared->flight_mode, window, &trace);
    const Tangent tangent(wrapped);
    typename System::State x0{};
    std::copy_n(x.begin(), n, x0.begin());
    EventLog log(true);
    const int sample_count = detailed ? samples_per_period * shared->period - 1 : 0;
    GapSampler<System> sampler(system, shared->flight_mode, t0, span / (sample_count + 1),
                               sample_count);
    const auto run = with_stepper<Tangent>(
        shared->setup.method, stepper_settings(tangent, shared->setup), [&](auto& stepper) {
          return simulate(tangent, stepper, tangent.start(x0, shared->flight_mode),
                          shared->flight_mode, t0, t0 + span, loop_options(shared->setup), log,
                          sampler);
        });
    if (run.termination != Termination::completed || run.mode != shared->flight_mode) return result;
    const auto state = Tangent::base_state(run.state);
    result.completed = std::all_of(state.begin(), state.begin() + n,
                                   [](double component) { return std::isfinite(component); });
    result.image.assign(state.begin(), state.begin() + n);
    for (const auto& row : Tangent::fundamental_matrix(run.state))
      result.monodromy.emplace_back(row.begin(), row.end());
    result.span = span;
    result.omega = omega;
    for (const EventRecord& event : log.records()) {
      result.event_times.push_back(event.t - t0);
      const std::string wall = event.wall > 0 ? "+" + std::to_string(event.wall)
                                              : std::to_string(event.wall);
      if (event.kind == EventKind::impact) {
        ++result.impacts;
        result.signature += (result.signature.empty() ? "" : " ") + wall;
      } else if (event.kind == EventKind::contact_start) {
        ++result.contact_phases;
        result.signature += (result.signature.empty() ? "c" : " c") + wall;
      }
    }
    for (const auto& crossing : trace.crossings) {
      if (crossing.speed < result.min_impact_speed) {
        result.min_impact_speed = crossing.speed;
        result.slowest_impact_time = crossing.t - t0;
        result.slowest_impact_witness = crossing.witness;
      }
    }
    // interior local minima of each gap between samples in flight, away from crossings
    const auto& samples = sampler.samples;
    for (std::size_t j = 1; j + 1 < samples.size(); ++j) {
      if (!samples[j - 1].flight || !samples[j].flight || !samples[j + 1].flight) continue;
      for (std::size_t k = 0; k < System::max_witnesses; ++k) {
        const double a = samples[j - 1].gap[k], b = samples[j].gap[k], c = samples[j + 1].gap[k];
        if (!(b <= a && b <= c) || !std::isfinite(a + b + c)) continue;
        const bool crossed = std::any_of(
            trace.crossings.begin(), trace.crossings.end(), [&](const auto& crossing) {
              return crossing.witness == static_cast<int>(k) && crossing.t >= samples[j - 1].t &&
                     crossing.t <= samples[j + 1].t;
            });
        if (crossed) continue;
        // the parabola through the three samples
        const double curvature = a - 2.0 * b + c;
        const double offset = curvature > 0.0 ? 0.5 * (a - c) / curvature : 0.0;
        const double lowest = b - 0.125 * (a - c) * offset;
        if (lowest < result.min_flight_gap) {
          result.min_flight_gap = lowest;
          result.min_flight_gap_time = samples[j].t + offset * (samples[j + 1].t - samples[j].t) - t0;
          result.min_flight_gap_witness = static_cast<int>(k);
        }
      }
    }
    return result;
  };
  problem.gap_at = [shared](const OrbitPoint& x, double p, double section_phase,
                            const ContactWindow& suppressed, double t) {
    GapSample sample;
    const System system = shared->make_system(p);
    const double t0 = section_phase / forcing_omega_of(system);
    ContactWindow window = suppressed;
    window.from += t0;
    window.to += t0;
    const Wrapped wrapped(system, shared->flight_mode, window, nullptr);
    typename System::State x0{};
    std::copy_n(x.begin(), n, x0.begin());
    EventLog log(false);
    const auto run = with_stepper<Wrapped>(
        shared->setup.method, stepper_settings(wrapped, shared->setup), [&](auto& stepper) {
          return simulate(wrapped, stepper, x0, shared->flight_mode, t0, t0 + t,
                          loop_options(shared->setup), log);
        });
    if (run.termination != Termination::completed || run.mode != shared->flight_mode ||
        suppressed.witness < 0)
      return sample;
    const WitnessSample h =
        system.witness(run.mode, static_cast<std::size_t>(suppressed.witness), run.state, t0 + t);
    sample.completed = true;
    sample.value = h.value;
    sample.rate = h.rate;
    return sample;
  };
  problem.transport = [shared](const OrbitPoint& x, double p, double from,
                               double to) -> std::optional<OrbitPoint> {
    const System system = shared->make_system(p);
    const double omega = forcing_omega_of(system);
    const double shift = std::remainder(to - from, 2.0 * std::numbers::pi);
    const double t0 = from / omega;
    const double t1 = t0 + (shift < 0.0 ? shift + 2.0 * std::numbers::pi : shift) / omega;
    typename System::State x0{};
    std::copy_n(x.begin(), n, x0.begin());
    EventLog log(false);
    const auto run = with_stepper<System>(
        shared->setup.method, stepper_settings(system, shared->setup), [&](auto& stepper) {
          return simulate(system, stepper, x0, shared->flight_mode, t0, t1,
                          loop_options(shared->setup), log);
        });
    if (run.termination != Termination::completed) return std::nullopt;
    return OrbitPoint(run.state.begin(), run.state.begin() + n);
  };
  return problem;
}

// The curve of the first located fold, period doubling or grazing point (of
// job.curve_type where given) of the first branch, in (job.parameter,
// job.second_parameter), into result.curve (result.curve_note says why not).
template <HasJacobian System, class SystemAt>
void continue_curve_of(ContinuationJobResult& result, SystemAt system_at,
                       typename System::Mode flight_mode, const Scene& scene,
                       const ContinuationJob& job, const FlowSetup& setup, double omega) {
  const ContinuationResult& branch = result.branches.front().result;
  const auto wanted = [&](const BifurcationPoint& p) {
    if (!p.located) return false;
    const std::string type = p.type == "branch_point" ? "fold" : p.type;
    if (!job.curve_type.empty()) return type == job.curve_type;
    return type == "fold" || type == "period_doubling" || type == "grazing";
  };
  const auto found = std::find_if(branch.points.begin(), branch.points.end(), wanted);
  if (found == branch.points.end()) {
    result.curve_note = "no located " +
                        (job.curve_type.empty() ? std::string("fold, period doubling or grazing")
                                                : job.curve_type) +
                        " point on the branch to start the curve from";
    return;
  }
  CurveRequest request;
  request.type = found->type == "branch_point" ? "fold" : found->type;
  request.from1 = job.from;
  request.to1 = job.to;
  request.from2 = job.second_from;
  request.to2 = job.second_to;
  request.p1 = found->parameter;
  request.state = found->state;
  request.graze_time = found->graze_time;
  request.graze_witness = found->graze_witness;
  request.max_points = job.numerics.max_points;
  request.tolerance = job.numerics.tolerance;
  // the branch's largest step, as a fraction of the first parameter's range
  if (job.numerics.max_step > 0.0) request.max_step = job.numerics.max_step / std::fabs(job.to - job.from);
  TwoParameterProblem problem;
  problem.at = [scene, job, system_at, flight_mode, setup, omega](double p2) {
    auto make_system = [scene, job, system_at, p2](double p1) {
      Scene at = scene;
      at.values[job.parameter] = p1;
      at.values[job.second_parameter] = p2;
      return system_at(at);
    };
    return section_map_problem<System>(make_system, flight_mode, setup, job.phase, job.period,
                                       omega);
  };
  result.curve = continue_curve(problem, request);
  result.has_curve = true;
}

// A boundary in terms of the scene (ParameterBoundary): `value(scene)` changes
// sign where it is crossed, as a function of the continued key alone.
struct SceneBoundary {
  std::string type, note;
  double (*value)(const Scene& scene) = nullptr;
};

// A continuation from a scene: the start from a transient from the scene's
// initial state at p = from (or the job's start), the branch, then, for each
// period doubling asked for, the doubled orbit's branch from the first period
// doubling located on the previous one (along the −1 eigenvector).
// system_at(scene) builds the system a scene describes.
template <HybridSystem System, class SystemAt>
ContinuationJobResult run_continuation(SystemAt system_at, typename System::Mode flight_mode,
                                       const typename System::State& initial_state,
                                       const Scene& job_scene, const ContinuationJob& job,
                                       const std::vector<SceneBoundary>& boundaries = {}) {
  ContinuationJobResult result;
  // a two-parameter job runs its branch at second_parameter = second_from
  Scene scene = job_scene;
  if (!job.second_parameter.empty()) scene.values[job.second_parameter] = job.second_from;
  if constexpr (!HasJacobian<System>) {
    result.note = "this oscillator/model has no Jacobians";
    return result;
  } else {
    result.available = true;
    Scene start_scene = scene;
    start_scene.values[job.parameter] = job.from;
    const System start_system = system_at(start_scene);
    const double omega = forcing_omega_of(start_system);
    const FlowSetup setup = flow_setup(scene);
    ContinuationRequest request = job.numerics;
    request.from = job.from;
    request.to = job.to;
    constexpr std::size_t n = tangent_dimension_of<System>;
    result.dimension = n;
    if (job.has_start) {
      if (job.start.size() != n)
        throw BadInput("start", std::to_string(job.start.size()) + " numbers",
                       "expected " + std::to_string(n) + " (the orbit's state on the section)");
      request.start = job.start;
    } else {
      const double forcing_period = 2.0 * std::numbers::pi / omega;
      const double t0 = start_scene.number("t0");
      const double after = t0 + job.transient_periods * forcing_period;
      const double k =
          std::ceil((omega * after - job.phase) / (2.0 * std::numbers::pi) - 1e-9);
      const double t_section = (job.phase + 2.0 * std::numbers::pi * k) / omega;
      EventLog log(false);
      const auto transient = with_stepper<System>(
          setup.method, stepper_settings(start_system, setup), [&](auto& stepper) {
            return simulate(start_system, stepper, initial_state, flight_mode, t0, t_section,
                            loop_options(setup), log);
          });
      request.start.assign(transient.state.begin(), transient.state.begin() + n);
    }
    auto problem_for = [&](int period) {
      auto make_system = [scene, parameter = job.parameter, system_at](double p) {
        Scene at = scene;
        at.values[parameter] = p;
        return system_at(at);
      };
      ContinuationProblem problem = section_map_problem<System>(make_system, flight_mode, setup,
                                                                job.phase, period, omega);
      for (const SceneBoundary& boundary : boundaries)
        problem.boundaries.push_back(
            {boundary.type, boundary.note,
             [scene, parameter = job.parameter, value = boundary.value](double p) {
               Scene at = scene;
               at.values[parameter] = p;
               return value(at);
             }});
      return problem;
    };
    int period = job.period;
    result.branches.push_back({period, continue_branch(problem_for(period), request)});
    for (int doubling = 0; doubling < job.doublings; ++doubling) {
      const ContinuationResult& previous = result.branches.back().result;
      const auto found = std::find_if(
          previous.points.begin(), previous.points.end(),
          [](const BifurcationPoint& p) { return p.type == "period_doubling" && p.located; });
      if (found == previous.points.end()) break;
      const BifurcationPoint doubling_point = *found;
      // the monodromy of the n-fold map at the point, for the −1 eigenvector
      const ContinuationProblem problem = problem_for(period);
      const OrbitEvaluation at = problem.evaluate(doubling_point.state, doubling_point.parameter,
                                                  job.phase, false, {});
      std::vector<double> direction = eigenvector_for(at.monodromy, -1.0);
      direction.push_back(0.0);  // dp = 0
      period *= 2;
      ContinuationRequest doubled = request;
      doubled.from = doubling_point.parameter;
      result.branches.push_back(
          {period, continue_branch_from(problem_for(period), doubled, doubling_point.state,
                                        doubling_point.parameter, direction)});
    }
    if (!job.second_parameter.empty())
      continue_curve_of<System>(result, system_at, flight_mode, scene, job, setup, omega);
    return result;
  }
}

}  // namespace impactlab
