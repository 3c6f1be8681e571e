// The flows (simulate/flow.hpp) that the analyses of this folder run for a
// system S: S itself, and the decorated systems they build on it. A binding
// compiles them once, in its own translation unit, with the one line that
// fits its system:
//
//   IMPACTLAB_SIMULATION_FLOW_ENGINES(S)  simulate only
//   IMPACTLAB_SECTION_FLOW_ENGINES(S)     and sections, sweeps, basins (no Jacobians)
//   IMPACTLAB_TANGENT_FLOW_ENGINES(S)     and Lyapunov exponents, periodic orbits,
//                                         continuation (S has Jacobians)
//   IMPACTLAB_IMPACT_SECTION_FLOW_ENGINES(S)  and continuation on the impact
//                                         section (S's tangent space has dimension 2)
//
// A new analysis that decorates a system another way adds its type here; no
// binding changes. A flow that is missing fails to link, naming the type.
#pragma once

#include <impactlab/analysis/crossing_section.hpp>
#include <impactlab/analysis/run_continuation.hpp>
#include <impactlab/analysis/variational.hpp>
#include <impactlab/simulate/flow_engines.hpp>

#define IMPACTLAB_SIMULATION_FLOW_ENGINES(...) IMPACTLAB_FLOW_ENGINES(__VA_ARGS__)

#define IMPACTLAB_SECTION_FLOW_ENGINES(...)  \
  IMPACTLAB_SIMULATION_FLOW_ENGINES(__VA_ARGS__); \
  IMPACTLAB_FLOW_ENGINES(::impactlab::CrossingSection<__VA_ARGS__>)

#define IMPACTLAB_TANGENT_FLOW_ENGINES(...)                                                     \
  IMPACTLAB_SECTION_FLOW_ENGINES(__VA_ARGS__);                                                  \
  IMPACTLAB_FLOW_ENGINES(::impactlab::Variational<__VA_ARGS__>);                                \
  IMPACTLAB_FLOW_ENGINES(::impactlab::SuppressedContacts<__VA_ARGS__>);                         \
  IMPACTLAB_FLOW_ENGINES(::impactlab::Variational<::impactlab::SuppressedContacts<__VA_ARGS__>>)

// continuation on the impact section (one degree of freedom: a tangent space of 2)
#define IMPACTLAB_IMPACT_SECTION_FLOW_ENGINES(...)                                  \
  IMPACTLAB_FLOW_ENGINES(                                                           \
      ::impactlab::StopAtWallImpact<::impactlab::SuppressedContacts<__VA_ARGS__>>); \
  IMPACTLAB_FLOW_ENGINES(::impactlab::Variational<                                  \
                         ::impactlab::StopAtWallImpact<::impactlab::SuppressedContacts<__VA_ARGS__>>>)
