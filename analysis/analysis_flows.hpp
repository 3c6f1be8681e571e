// The flows (simulate/flow.hpp) that the analyses of this folder run for a
// system S: S itself, S decorated (analysis/decorated_system.hpp: a crossing
// section, suppressed contacts, a stop at a wall impact, each switched on at
// run time), and the variational equations of the decorated S. A binding
// compiles them once, in its own translation unit, with the one line that
// fits its system:
//
//   IMPACTLAB_SIMULATION_FLOW_ENGINES(S)  simulate only
//   IMPACTLAB_SECTION_FLOW_ENGINES(S)     and sections, sweeps, basins (no Jacobians)
//   IMPACTLAB_TANGENT_FLOW_ENGINES(S)     and Lyapunov exponents, periodic orbits,
//                                         continuation (S has Jacobians)
//
// A new analysis that decorates a system another way adds its decoration to
// DecoratedSystem; no binding changes. A flow that is missing fails to link,
// naming the type.
#pragma once

#include <impactlab/analysis/decorated_system.hpp>
#include <impactlab/analysis/variational.hpp>
#include <impactlab/simulate/flow_engines.hpp>

#define IMPACTLAB_SIMULATION_FLOW_ENGINES(...) IMPACTLAB_FLOW_ENGINES(__VA_ARGS__)

#define IMPACTLAB_SECTION_FLOW_ENGINES(...)       \
  IMPACTLAB_SIMULATION_FLOW_ENGINES(__VA_ARGS__); \
  IMPACTLAB_FLOW_ENGINES(::impactlab::DecoratedSystem<__VA_ARGS__>)

#define IMPACTLAB_TANGENT_FLOW_ENGINES(...)    \
  IMPACTLAB_SECTION_FLOW_ENGINES(__VA_ARGS__); \
  IMPACTLAB_FLOW_ENGINES(::impactlab::Variational<::impactlab::DecoratedSystem<__VA_ARGS__>>)
