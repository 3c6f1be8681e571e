// The flows of the bouncing ball, for every analysis (analysis/analysis_flows.hpp).
#include <impactlab/analysis/analysis_flows.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>

IMPACTLAB_TANGENT_FLOW_ENGINES(impactlab::BouncingBall);
