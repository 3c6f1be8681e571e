// The Dormand–Prince 5(4) stepper, compiled once for each state type of
// integrate/state_dimensions.hpp.
#include <impactlab/integrate/odeint_dopri5.hpp>

namespace impactlab {

#define IMPACTLAB_DEFINE_DOPRI5(N) template class OdeintDopri5<std::array<double, N>>;
IMPACTLAB_FOR_EACH_STATE_DIMENSION(IMPACTLAB_DEFINE_DOPRI5)
#undef IMPACTLAB_DEFINE_DOPRI5

}  // namespace impactlab
