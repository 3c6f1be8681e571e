// The flows of the pendulum's Model N, for every analysis
// (analysis/analysis_flows.hpp), in two units: here the model and the
// decorated model; its variational equations in
// pendulum_newton_variational_flows.cpp (in one unit they took twice as long
// to compile as a typical unit).
#include <impactlab/analysis/analysis_flows.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

IMPACTLAB_SECTION_FLOW_ENGINES(impactlab::PendulumWalls);
