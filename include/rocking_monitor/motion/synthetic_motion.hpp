#pragma once

// Synthetic ground-acceleration signals for test inputs and the committed synthetic bags.
// Everything is deterministic: the noise uses std::mt19937_64 (its output sequence is fixed by the
// C++ standard) and its own polar Box-Muller transform, because the standard library's
// normal_distribution is implementation defined and could differ between compilers. (Only std::log
// may differ in the last bit between C libraries; the committed bags are the reference.)

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace rocking_monitor::core {

/// Sample times 0, dt, ..., duration (inclusive): round(duration / dt) + 1 samples.
/// Throws std::invalid_argument unless dt > 0 and duration >= 0 are finite.
std::size_t synthetic_sample_count(double duration_s, double dt_s);

/// Ricker wavelet (the negative normalised second derivative of a Gaussian, "Mexican hat"):
///   a(t) = peak (1 - 2 u) exp(-u),  u = (pi f (t - center))^2,
/// peak m/s^2 at t = center, peak frequency f Hz (of its Fourier amplitude spectrum), two side lobes
/// of -0.446 peak at t = center +- sqrt(3/2) / (pi f). Throws std::invalid_argument for f <= 0.
double ricker(double t, double peak_mps2, double frequency_hz, double center_s);

/// `cycles` full sine cycles of amplitude A and period T starting at `start`, zero elsewhere:
///   a(t) = A sin(2 pi (t - start) / T) for start <= t <= start + cycles T.
/// Throws std::invalid_argument for T <= 0 or cycles < 0.
double sine_pulse(double t, double amplitude_mps2, double period_s, double start_s, double cycles);

/// Zero-mean Gaussian white noise with standard deviation `rms`, reproducible from `seed`.
class GaussianNoise {
 public:
  GaussianNoise(double rms, std::uint64_t seed);
  double next();

 private:
  double rms_;
  std::mt19937_64 engine_;
  bool have_spare_ = false;
  double spare_ = 0.0;
  double uniform();  ///< in (-1, 1) from the top 53 bits
};

}  // namespace rocking_monitor::core
