// The flows of the pendulum's Model N, for every analysis (analysis/analysis_flows.hpp).
#include <impactlab/analysis/analysis_flows.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

IMPACTLAB_TANGENT_FLOW_ENGINES(impactlab::PendulumWalls);
