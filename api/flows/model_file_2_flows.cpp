// The flows of a model file's two-state systems, for every analysis (analysis/analysis_flows.hpp).
#include <impactlab/analysis/analysis_flows.hpp>
#include <impactlab/oscillators/model_file/model_system.hpp>

IMPACTLAB_TANGENT_FLOW_ENGINES(impactlab::ModelSystem<2>);
