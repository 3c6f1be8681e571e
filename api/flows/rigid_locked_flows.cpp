// The flows of the pendulum's rigid-body model with the spin locked, for every
// analysis (analysis/analysis_flows.hpp), in three units, each about as long
// to compile as the Taylor stepper on the variational equations alone (all in
// one unit took three times as long): here its variational equations with
// every stepper but Taylor; the model, which runs as the decorated model, in
// rigid_locked_decorated_flows.cpp; the variational equations with the Taylor
// stepper in rigid_locked_variational_taylor_flows.cpp.
#include <impactlab/analysis/analysis_flows.hpp>
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_spin.hpp>

IMPACTLAB_EXTERN_VARIATIONAL_STEPPED_FLOW_ENGINE(taylor, impactlab::LockedSpinPendulum);
IMPACTLAB_VARIATIONAL_FLOW_ENGINES(impactlab::LockedSpinPendulum);
