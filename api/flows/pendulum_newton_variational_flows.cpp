// The variational equations of the pendulum's Model N (pendulum_newton_flows.cpp
// says why they have a unit of their own).
#include <impactlab/analysis/analysis_flows.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

IMPACTLAB_VARIATIONAL_FLOW_ENGINES(impactlab::PendulumWalls);
