// The flows of the linear impact oscillator, for every analysis (analysis/analysis_flows.hpp).
#include <impactlab/analysis/analysis_flows.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>

IMPACTLAB_TANGENT_FLOW_ENGINES(impactlab::LinearImpact);
