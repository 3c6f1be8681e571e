// The Fehlberg 7(8) stepper's constructors, compiled once (see CMakeLists.txt
// for why they live apart).
#include "integrate/odeint_fehlberg78.hpp"

namespace impactlab {

template class OdeintFehlberg78<std::array<double, 2>>;
template class OdeintFehlberg78<std::array<double, 3>>;

}  // namespace impactlab
