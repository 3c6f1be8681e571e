// The flows of the pendulum's rigid-body model (simulations only), for every analysis (analysis/analysis_flows.hpp).
#include <impactlab/analysis/analysis_flows.hpp>
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_walls.hpp>

IMPACTLAB_SIMULATION_FLOW_ENGINES(impactlab::RigidPendulumWalls);
