// Test support: the period-1 orbit with one impact per forcing period of the
// linear impact oscillator ẍ + 2ζẋ + x = A cos ωt, stop at σ, ẋ⁺ = −r ẋ⁻, in
// closed form (derived here: the damped oscillator's transition matrix over
// one forcing period, the particular solution as a complex amplitude, the
// impact phase solved by TOMS 748), and its Floquet multipliers from the
// textbook saltation matrix of a Newton impact on a fixed stop. Independent
// of the toolkit's integrators and variational equations.
#pragma once

#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <optional>
#include <utility>

#include <boost/math/tools/roots.hpp>

#include <impactlab/oscillators/linear_impact/linear_impact.hpp>

namespace impactlab::testing {

using Complex = std::complex<double>;

double root_by_toms748(auto&& f, double a, double b) {
  std::uintmax_t iterations = 200;
  const auto bracket = boost::math::tools::toms748_solve(
      f, a, b, boost::math::tools::eps_tolerance<double>(52), iterations);
  return 0.5 * (bracket.first + bracket.second);
}

// The period-1 orbit with one impact per period of ẍ + 2ζẋ + x = A cos ωt,
// stop at σ, ẋ⁺ = −r ẋ⁻, in closed form.
struct ClosedFormOrbit {
  double impact_time;  // t* in [0, T)
  double velocity;     // ẋ⁻ > 0 at the impact
  std::array<Complex, 2> multipliers;
  double trace, determinant;  // of the monodromy matrix
};

class LinearImpactClosedForm {
 public:
  explicit LinearImpactClosedForm(const LinearImpactParameters& p)
      : p_(p),
        period_(2.0 * std::numbers::pi / p.omega),
        amplitude_(p.A / Complex(1.0 - p.omega * p.omega, 2.0 * p.zeta * p.omega)) {
    // transition matrix of u'' + 2ζu' + u = 0 over one forcing period
    const double wd = std::sqrt(1.0 - p.zeta * p.zeta);
    const double decay = std::exp(-p.zeta * period_);
    const double c = std::cos(wd * period_), s = std::sin(wd * period_);
    phi_ = {{{decay * (c + p.zeta / wd * s), decay * s / wd},
             {-decay * s / wd, decay * (c - p.zeta / wd * s)}}};
  }

  [[nodiscard]] double particular_x(double t) const {
    return (amplitude_ * std::exp(Complex(0.0, p_.omega * t))).real();
  }
  [[nodiscard]] double particular_v(double t) const {
    return (Complex(0.0, p_.omega) * amplitude_ * std::exp(Complex(0.0, p_.omega * t))).real();
  }

  // ẋ⁻ that closes the position equation for an impact at t; F(t) closes the velocity one
  [[nodiscard]] double velocity_for(double t) const {
    const double a = p_.sigma - particular_x(t), vp = particular_v(t);
    return ((phi_[0][0] - 1.0) * a - phi_[0][1] * vp) / (p_.r * phi_[0][1]);
  }
  [[nodiscard]] double velocity_residual(double t) const {
    const double a = p_.sigma - particular_x(t), vp = particular_v(t);
    const double v = velocity_for(t);
    return phi_[1][0] * a + phi_[1][1] * (-p_.r * v - vp) - (v - vp);
  }

  // position between impacts, from just after the impact at t*
  [[nodiscard]] std::pair<double, double> state_after(double t_star, double v, double tau) const {
    const double wd = std::sqrt(1.0 - p_.zeta * p_.zeta);
    const double u0 = p_.sigma - particular_x(t_star);
    const double du0 = -p_.r * v - particular_v(t_star);
    const double decay = std::exp(-p_.zeta * tau);
    const double c = std::cos(wd * tau), s = std::sin(wd * tau);
    const double u = decay * ((c + p_.zeta / wd * s) * u0 + s / wd * du0);
    const double du = decay * (-s / wd * u0 + (c - p_.zeta / wd * s) * du0);
    return {u + particular_x(t_star + tau), du + particular_v(t_star + tau)};
  }

  // the admissible orbit: ẋ⁻ > 0 and x < σ strictly between impacts
  [[nodiscard]] std::optional<ClosedFormOrbit> orbit() const {
    const int grid = 2000;
    for (int k = 0; k < grid; ++k) {
      const double a = period_ * k / grid, b = period_ * (k + 1) / grid;
      const double fa = velocity_residual(a), fb = velocity_residual(b);
      if (!(fa * fb < 0.0)) continue;
      const double t = root_by_toms748([&](double x) { return velocity_residual(x); }, a, b);
      const double v = velocity_for(t);
      if (!(v > 0.0)) continue;
      bool admissible = true;
      for (int j = 1; j < 400 && admissible; ++j)
        admissible = state_after(t, v, period_ * j / 400).first < p_.sigma;
      if (!admissible) continue;
      ClosedFormOrbit orbit{t, v, {}, 0.0, 0.0};
      // S = [[−r, 0], [(1 + r)(A cos ωt* − σ)/v, −r]], monodromy S Φ
      const double s21 = (1.0 + p_.r) * (p_.A * std::cos(p_.omega * t) - p_.sigma) / v;
      const double m11 = -p_.r * phi_[0][0], m12 = -p_.r * phi_[0][1];
      const double m21 = s21 * phi_[0][0] - p_.r * phi_[1][0];
      const double m22 = s21 * phi_[0][1] - p_.r * phi_[1][1];
      orbit.trace = m11 + m22;
      orbit.determinant = m11 * m22 - m12 * m21;
      const Complex root = std::sqrt(Complex(orbit.trace * orbit.trace / 4.0 - orbit.determinant));
      orbit.multipliers = {orbit.trace / 2.0 + root, orbit.trace / 2.0 - root};
      if (std::abs(orbit.multipliers[1]) > std::abs(orbit.multipliers[0]))
        std::swap(orbit.multipliers[0], orbit.multipliers[1]);
      return orbit;
    }
    return std::nullopt;
  }

  [[nodiscard]] double period() const { return period_; }

 private:
  LinearImpactParameters p_;
  double period_;
  Complex amplitude_;
  std::array<std::array<double, 2>, 2> phi_;
};

}  // namespace impactlab::testing
