// The flows of the pendulum's Model P (no Jacobians: no tangent flows), for every analysis (analysis/analysis_flows.hpp).
#include <impactlab/analysis/analysis_flows.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

IMPACTLAB_SECTION_FLOW_ENGINES(impactlab::PaperPendulumWalls);
