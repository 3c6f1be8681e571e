// The flows (simulate/flow.hpp) that the analyses of this folder run for a
// system S: S itself, S decorated (analysis/decorated_system.hpp: a crossing
// section, suppressed contacts, a stop at a wall impact, each switched on at
// run time), and the variational equations of the decorated S. S's own flows
// run as S decorated with nothing switched on, which is S number for number,
// so that the event loop is compiled for S once, not twice
// (simulate/flow_engines.hpp, FlowRunner). A binding compiles them once, in
// its own translation unit, with the one line that fits its system:
//
//   IMPACTLAB_SIMULATION_FLOW_ENGINES(S)  simulate, sections, sweeps, basins
//   IMPACTLAB_SECTION_FLOW_ENGINES(S)     the same (no Jacobians)
//   IMPACTLAB_TANGENT_FLOW_ENGINES(S)     and Lyapunov exponents, periodic orbits,
//                                         continuation (S has Jacobians)
//
// A system whose flows take too long to compile in one unit (the pendulum's
// Model N and its rigid-body model: their variational equations, in Taylor
// series above all) spreads them over a few units with the lines
// IMPACTLAB_TANGENT_FLOW_ENGINES is made of:
//
//   IMPACTLAB_SIMULATION_FLOW_ENGINES(S)   S and S decorated
//   IMPACTLAB_VARIATIONAL_FLOW_ENGINES(S)  its variational equations
//
// and can take one stepper's engine of the variational equations further,
// into a unit of its own: IMPACTLAB_VARIATIONAL_STEPPED_FLOW_ENGINE(METHOD, S)
// there, and IMPACTLAB_EXTERN_VARIATIONAL_STEPPED_FLOW_ENGINE(METHOD, S)
// before IMPACTLAB_VARIATIONAL_FLOW_ENGINES(S) (api/flows/rigid_free_flows.cpp).
//
// A new analysis that decorates a system another way adds its decoration to
// DecoratedSystem; no binding changes. A flow that is missing fails to link,
// naming the type.
#pragma once

#include <impactlab/analysis/decorated_system.hpp>
#include <impactlab/analysis/variational.hpp>
#include <impactlab/simulate/flow_engines.hpp>

#define IMPACTLAB_SIMULATION_FLOW_ENGINES(...)                                       \
  IMPACTLAB_FLOW_ENGINES(::impactlab::DecoratedSystem<__VA_ARGS__>);                   \
  template <>                                                                        \
  struct impactlab::FlowRunner<__VA_ARGS__> {                                        \
    using type = ::impactlab::DecoratedSystem<__VA_ARGS__>;                          \
  };                                                                                 \
  IMPACTLAB_FLOW_ENGINES(__VA_ARGS__)

#define IMPACTLAB_VARIATIONAL_FLOW_ENGINES(...) \
  IMPACTLAB_FLOW_ENGINES(::impactlab::Variational<::impactlab::DecoratedSystem<__VA_ARGS__>>)

#define IMPACTLAB_SECTION_FLOW_ENGINES(...) IMPACTLAB_SIMULATION_FLOW_ENGINES(__VA_ARGS__)

#define IMPACTLAB_TANGENT_FLOW_ENGINES(...)    \
  IMPACTLAB_SECTION_FLOW_ENGINES(__VA_ARGS__); \
  IMPACTLAB_VARIATIONAL_FLOW_ENGINES(__VA_ARGS__)

// one stepper's engine (METHOD: an integrator.method) of the variational
// equations: compiled in this unit; declared compiled in another
#define IMPACTLAB_VARIATIONAL_STEPPED_FLOW_ENGINE(METHOD, ...) \
  IMPACTLAB_STEPPED_FLOW_ENGINE(                               \
      METHOD, ::impactlab::Variational<::impactlab::DecoratedSystem<__VA_ARGS__>>)
#define IMPACTLAB_EXTERN_VARIATIONAL_STEPPED_FLOW_ENGINE(METHOD, ...) \
  IMPACTLAB_EXTERN_STEPPED_FLOW_ENGINE(                               \
      METHOD, ::impactlab::Variational<::impactlab::DecoratedSystem<__VA_ARGS__>>)
