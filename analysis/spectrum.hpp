// Amplitude spectra of a sampled response (FFTW's real-to-complex transform).
//
// For n samples x_j = x(t0 + j Δt) the line k (k = 0 … n/2) sits at the
// angular frequency ω_k = 2πk / (n Δt) with the one-sided amplitude
// |X_k| · 2/n (|X_0| / n for the mean, and for k = n/2 when n is even), so a
// component a cos(ω_k t + φ) shows as a line of height a. Sampling a whole
// number of forcing periods puts the harmonics of a period-n orbit, kω/n,
// exactly on lines: no window is applied (nor needed) then.
#pragma once

#include <span>
#include <vector>

namespace impactlab {

struct SpectrumLine {
  double angular_frequency;  // rad per time unit
  double amplitude;          // in the units of the samples
};

// Throws std::invalid_argument for fewer than two samples or Δt <= 0.
std::vector<SpectrumLine> amplitude_spectrum(std::span<const double> samples,
                                             double sample_interval);

}  // namespace impactlab
