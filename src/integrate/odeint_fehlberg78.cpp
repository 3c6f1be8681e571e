// The Fehlberg 7(8) stepper's constructor, compiled once (see CMakeLists.txt
// for why they live apart).
#include <impactlab/integrate/odeint_fehlberg78.hpp>

namespace impactlab {

#define IMPACTLAB_DEFINE_FEHLBERG78(N) \
  template OdeintFehlberg78<std::array<double, N>>::OdeintFehlberg78(const StepperSettings&);
IMPACTLAB_FOR_EACH_STATE_DIMENSION(IMPACTLAB_DEFINE_FEHLBERG78)
#undef IMPACTLAB_DEFINE_FEHLBERG78

}  // namespace impactlab
