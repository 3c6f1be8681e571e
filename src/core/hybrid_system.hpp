// The hybrid-system concept: modes, a vector field per mode, witness functions
// with a trigger direction, and a transition (reset map) per event.
//
// Every oscillator in `oscillators/` models this concept; the one event loop in
// `simulate/simulator.hpp` runs any of them. The state is a fixed-size
// std::array so that the right-hand side inlines and nothing is allocated per
// step (Boost.Odeint's array algebra works on it directly).
#pragma once

#include <array>
#include <concepts>
#include <cstddef>

#include <impactlab/core/event_log.hpp>

namespace impactlab {

// Which sign change of a witness function is an event.
enum class TriggerDirection {
  falling,  // from > 0 to <= 0 (a gap closing, a normal force vanishing)
  rising,   // from < 0 to >= 0
  either,   // any sign change (a tangential velocity reversing)
};

// A witness function's value and its time derivative along the flow of the
// current mode. The rate is what lets the event locator bracket extrema of the
// witness inside one step, so that a grazing contact (a double root) is seen.
// A system may write its witnesses over a number type (a Taylor series type
// runs through them, integrate/taylor_series.hpp): BasicWitnessSample<Number>.
template <class Number>
struct BasicWitnessSample {
  Number value{};
  Number rate{};
};
using WitnessSample = BasicWitnessSample<double>;

// How a witness reached zero.
enum class CrossingKind {
  crossing,    // a sign change in the trigger direction
  grazing,     // an extremum of the witness that touches zero within tolerance
  unresolved,  // past zero by more than the tolerance with no crossing found:
               // hops below round-off (an accumulation the model did not
               // resolve); the loop stops instead of letting the state through
};

// What the system does after an event: the state and mode to continue from,
// at `time` (>= the event time; later only when an accumulation of impacts was
// jumped over), or a request to stop the run with a typed diagnostic.
template <class State, class Mode>
struct Transition {
  State state{};
  Mode mode{};
  double time = 0.0;
  bool stop = false;
  // The event's tangent map is one side's only: the state before it sits on
  // a switch of the reset (an impulse on the friction cone's edge), where the
  // two sides give the same state but not the same derivative. The run goes
  // on; the analyses that report a linearisation (multipliers, Lyapunov
  // exponents) report Termination::no_tangent_map instead.
  bool one_sided = false;
};

// The concept itself. `Mode` is an enum; witness k of a mode is addressed by
// index; `max_witnesses` bounds the count for fixed-size scratch storage.
template <class S>
concept HybridSystem = requires(const S& system, const typename S::State& x,
                                typename S::State& dxdt, double t,
                                typename S::Mode mode, std::size_t k,
                                CrossingKind crossing, EventLog& log) {
  typename S::State;
  typename S::Mode;
  { S::max_witnesses } -> std::convertible_to<std::size_t>;
  { system.rhs(mode, x, dxdt, t) };
  { system.witness_count(mode) } -> std::convertible_to<std::size_t>;
  { system.witness(mode, k, x, t) } -> std::same_as<WitnessSample>;
  { system.trigger_direction(mode, k) } -> std::same_as<TriggerDirection>;
  { system.on_event(mode, k, crossing, x, t, log) }
      -> std::same_as<Transition<typename S::State, typename S::Mode>>;
  // Largest step the loop may take (s): a fraction of the forcing period, so
  // that witness extrema are resolved by the event locator's sampling.
  { system.max_step() } -> std::convertible_to<double>;
};

// Systems with a closed-form flow between events (used by method = "exact").
template <class S>
concept HasExactFlow = HybridSystem<S> &&
    requires(const S& system, typename S::Mode mode, const typename S::State& x0,
             double t0, double t, typename S::State& x) {
      { system.exact_flow(mode, x0, t0, t, x) };
    };

}  // namespace impactlab
