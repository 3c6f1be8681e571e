// Amplitude spectra: a sum of cosines of known amplitudes and phases comes
// back line for line; the response of a period-1 orbit (linear impact
// oscillator) has lines only at multiples of ω, that of the period-2 orbit of
// jin2003 at multiples of ω/2 with the odd ones present.
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/analysis/spectrum.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

TEST(Spectrum, SumOfCosinesComesBackLineForLine) {
  const int n = 256;
  const double dt = 0.01;
  const double base = 2.0 * std::numbers::pi / (n * dt);
  // mean 0.5, amplitude 1.25 on line 3, 0.3 on line 17, 0.07 on line 128 (Nyquist, cos only)
  std::vector<double> x(n);
  for (int j = 0; j < n; ++j) {
    const double t = j * dt;
    x[j] = 0.5 + 1.25 * std::cos(3 * base * t + 0.4) + 0.3 * std::cos(17 * base * t - 1.1) +
           0.07 * std::cos(128 * base * t);
  }
  const auto lines = impactlab::amplitude_spectrum(x, dt);
  ASSERT_EQ(lines.size(), 129u);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    EXPECT_NEAR(lines[k].angular_frequency, k * base, 1e-12 * k * base);
    const double expected = k == 0 ? 0.5 : k == 3 ? 1.25 : k == 17 ? 0.3 : k == 128 ? 0.07 : 0.0;
    EXPECT_NEAR(lines[k].amplitude, expected, 1e-12) << "line " << k;
  }
}

TEST(Spectrum, RejectsTooFewSamples) {
  const std::vector<double> one{1.0};
  EXPECT_THROW(impactlab::amplitude_spectrum(one, 0.1), std::invalid_argument);
}

// (harmonic, amplitude) rows of spectrum.csv from `impactlab spectrum ARGUMENTS`
std::vector<std::pair<double, double>> spectrum_of(const std::string& arguments) {
  const impactlab::testing::ScratchFolder scratch;
  const auto run = impactlab::testing::run_command_line(
      "spectrum " + arguments + " --quiet --out " + (scratch / "out").string());
  EXPECT_EQ(run.status, 0) << arguments << ": " << run.err;
  std::istringstream in(impactlab::testing::slurp(scratch / "out" / "spectrum.csv"));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "omega,amplitude,harmonic");
  std::vector<std::pair<double, double>> rows;
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::string omega, amplitude, harmonic;
    std::getline(fields, omega, ',');
    std::getline(fields, amplitude, ',');
    std::getline(fields, harmonic, ',');
    rows.emplace_back(std::stod(harmonic), std::stod(amplitude));
  }
  return rows;
}

// the largest amplitude off the multiples of 1/n, and the largest on them (n = period)
std::pair<double, double> off_and_on(const std::vector<std::pair<double, double>>& rows, int n) {
  double off = 0.0, on = 0.0;
  for (const auto& [harmonic, amplitude] : rows) {
    if (harmonic == 0.0) continue;
    const double multiple = harmonic * n;
    if (std::fabs(multiple - std::round(multiple)) < 1e-9)
      on = std::max(on, amplitude);
    else
      off = std::max(off, amplitude);
  }
  return {off, on};
}

TEST(Spectrum, PeriodOneOrbitHasLinesAtMultiplesOfOmegaOnly) {
  const auto rows = spectrum_of("linear_impact --transient 300 --periods 32");
  const auto [off, on] = off_and_on(rows, 1);
  EXPECT_GT(on, 0.1);
  EXPECT_LT(off, 1e-8 * on);
}

TEST(Spectrum, PeriodTwoOrbitOfThePendulumHasHalfHarmonics) {
  const auto rows = spectrum_of("jin2003 --transient 200 --periods 32");
  const auto [off, on] = off_and_on(rows, 2);
  EXPECT_LT(off, 1e-6 * on);
  // the line at ω/2 is there (it is the largest one)
  double half = 0.0;
  for (const auto& [harmonic, amplitude] : rows)
    if (std::fabs(harmonic - 0.5) < 1e-9) half = amplitude;
  EXPECT_EQ(half, on);
}

}  // namespace
