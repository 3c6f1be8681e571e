// The Bulirsch–Stoer stepper, compiled once for each state type of
// integrate/state_dimensions.hpp.
#include <impactlab/integrate/odeint_bulirsch_stoer.hpp>

namespace impactlab {

#define IMPACTLAB_DEFINE_BULIRSCH_STOER(N) template class OdeintBulirschStoer<std::array<double, N>>;
IMPACTLAB_FOR_EACH_STATE_DIMENSION(IMPACTLAB_DEFINE_BULIRSCH_STOER)
#undef IMPACTLAB_DEFINE_BULIRSCH_STOER

}  // namespace impactlab
