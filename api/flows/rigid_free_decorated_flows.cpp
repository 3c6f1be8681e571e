// The flows of the pendulum's rigid-body model with the spin free and of the
// decorated model, which runs them both (rigid_free_flows.cpp says why they
// have a unit of their own).
#include <impactlab/analysis/analysis_flows.hpp>
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_spin.hpp>

IMPACTLAB_SIMULATION_FLOW_ENGINES(impactlab::FreeSpinPendulum);
