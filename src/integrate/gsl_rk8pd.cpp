// GSL's rk8pd stepper, compiled once for each state type of
// integrate/state_dimensions.hpp.
#include <impactlab/integrate/gsl_rk8pd.hpp>

namespace impactlab {

#define IMPACTLAB_DEFINE_RK8PD(N) template class GslRk8pd<std::array<double, N>>;
IMPACTLAB_FOR_EACH_STATE_DIMENSION(IMPACTLAB_DEFINE_RK8PD)
#undef IMPACTLAB_DEFINE_RK8PD

}  // namespace impactlab
