// The fixed compile-time yardstick of benchmarks/compile_units.py: Eigen,
// Boost.Odeint rkf78 and dopri5 under their controllers, fmt. Compile times
// are stated as multiples of its time, measured in the same sitting. Not
// part of the build.
#include <Eigen/Dense>
#include <boost/numeric/odeint.hpp>
#include <fmt/format.h>
#include <array>
#include <cmath>
using State = std::array<double, 2>;
int main() {
  namespace ode = boost::numeric::odeint;
  State x{0.0, 0.1};
  auto rhs = [](const State& s, State& d, double t) { d[0] = s[1]; d[1] = -0.01 * s[1] - (9.81 - 1.5 * 7 * std::cos(7 * t)) * std::sin(s[0]) / 0.7; };
  auto stepper = ode::make_controlled(1e-10, 1e-12, ode::runge_kutta_fehlberg78<State>());
  ode::integrate_adaptive(stepper, rhs, x, 0.0, 10.0, 1e-3);
  auto d = ode::make_dense_output(1e-10, 1e-12, ode::runge_kutta_dopri5<State>());
  ode::integrate_adaptive(d, rhs, x, 0.0, 10.0, 1e-3);
  Eigen::Matrix4d m = Eigen::Matrix4d::Random(); Eigen::EigenSolver<Eigen::Matrix4d> es(m);
  fmt::print("{} {} {}\n", x[0], x[1], es.eigenvalues()(0).real());
}
