#include <impactlab/analysis/spectrum.hpp>

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include <fftw3.h>

namespace impactlab {

std::vector<SpectrumLine> amplitude_spectrum(std::span<const double> samples,
                                             double sample_interval) {
  const std::size_t n = samples.size();
  if (n < 2 || !(sample_interval > 0.0))
    throw std::invalid_argument("amplitude_spectrum: needs two or more samples and dt > 0");
  // FFTW's own aligned buffers; the plan destroys nothing of the input (copied)
  double* input = fftw_alloc_real(n);
  fftw_complex* output = fftw_alloc_complex(n / 2 + 1);
  fftw_plan plan;
  // planning is not thread-safe in FFTW 3; the transform itself is
#pragma omp critical(impactlab_fftw_plan)
  plan = fftw_plan_dft_r2c_1d(static_cast<int>(n), input, output, FFTW_ESTIMATE);
  for (std::size_t j = 0; j < n; ++j) input[j] = samples[j];
  fftw_execute(plan);
  std::vector<SpectrumLine> lines(n / 2 + 1);
  const double base = 2.0 * std::numbers::pi / (static_cast<double>(n) * sample_interval);
  for (std::size_t k = 0; k <= n / 2; ++k) {
    const double magnitude = std::hypot(output[k][0], output[k][1]);
    const bool unpaired = k == 0 || (n % 2 == 0 && k == n / 2);
    lines[k] = {base * static_cast<double>(k),
                magnitude * (unpaired ? 1.0 : 2.0) / static_cast<double>(n)};
  }
#pragma omp critical(impactlab_fftw_plan)
  fftw_destroy_plan(plan);
  fftw_free(input);
  fftw_free(output);
  return lines;
}

}  // namespace impactlab
