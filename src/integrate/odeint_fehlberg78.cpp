// The Fehlberg 7(8) stepper's constructor, compiled once (see CMakeLists.txt
// for why they live apart).
#include <impactlab/integrate/odeint_fehlberg78.hpp>

namespace impactlab {

template OdeintFehlberg78<std::array<double, 2>>::OdeintFehlberg78(const StepperSettings&);
template OdeintFehlberg78<std::array<double, 3>>::OdeintFehlberg78(const StepperSettings&);
template OdeintFehlberg78<std::array<double, 4>>::OdeintFehlberg78(const StepperSettings&);
template OdeintFehlberg78<std::array<double, 5>>::OdeintFehlberg78(const StepperSettings&);
// the variational states (analysis/variational.hpp): a 2- or 3-component state and Φ (2 × 2),
// the rigid pendulum's 5 components and Φ (2 × 2 with the spin locked, 3 × 3 free),
// a four-state model file's state and Φ (4 × 4)
template OdeintFehlberg78<std::array<double, 6>>::OdeintFehlberg78(const StepperSettings&);
template OdeintFehlberg78<std::array<double, 7>>::OdeintFehlberg78(const StepperSettings&);
template OdeintFehlberg78<std::array<double, 9>>::OdeintFehlberg78(const StepperSettings&);
template OdeintFehlberg78<std::array<double, 14>>::OdeintFehlberg78(const StepperSettings&);
template OdeintFehlberg78<std::array<double, 20>>::OdeintFehlberg78(const StepperSettings&);

}  // namespace impactlab
