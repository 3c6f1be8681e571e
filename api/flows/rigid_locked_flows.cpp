// The flows of the pendulum's rigid-body model with the spin locked, for every analysis (analysis/analysis_flows.hpp).
#include <impactlab/analysis/analysis_flows.hpp>
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_spin.hpp>

IMPACTLAB_TANGENT_FLOW_ENGINES(impactlab::LockedSpinPendulum);
