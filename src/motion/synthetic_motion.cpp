// Deterministic synthetic ground-acceleration signals (see synthetic_motion.hpp).

#include "rocking_monitor/motion/synthetic_motion.hpp"

#include <cmath>
#include <stdexcept>

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::core {

std::size_t synthetic_sample_count(double duration_s, double dt_s) {
  if (!(std::isfinite(dt_s) && dt_s > 0.0)) throw std::invalid_argument("sample interval must be finite and > 0 s");
  if (!(std::isfinite(duration_s) && duration_s >= 0.0)) throw std::invalid_argument("duration must be finite and >= 0 s");
  const double n = std::round(duration_s / dt_s);
  if (n > 1e9) throw std::invalid_argument("more than 1e9 samples requested");
  return static_cast<std::size_t>(n) + 1;
}

double ricker(double t, double peak_mps2, double frequency_hz, double center_s) {
  if (!(frequency_hz > 0.0) || !std::isfinite(frequency_hz)) throw std::invalid_argument("Ricker peak frequency must be > 0 Hz");
  const double x = kPi * frequency_hz * (t - center_s);
  const double u = x * x;
  return peak_mps2 * (1.0 - 2.0 * u) * std::exp(-u);
}

double sine_pulse(double t, double amplitude_mps2, double period_s, double start_s, double cycles) {
  if (!(period_s > 0.0) || !std::isfinite(period_s)) throw std::invalid_argument("sine pulse period must be > 0 s");
  if (!(cycles >= 0.0) || !std::isfinite(cycles)) throw std::invalid_argument("sine pulse cycles must be >= 0");
  const double tau = t - start_s;
  if (tau < 0.0 || tau > cycles * period_s) return 0.0;
  return amplitude_mps2 * std::sin(2.0 * kPi * tau / period_s);
}

GaussianNoise::GaussianNoise(double rms, std::uint64_t seed) : rms_(rms), engine_(seed) {
  if (!(rms >= 0.0) || !std::isfinite(rms)) throw std::invalid_argument("noise RMS must be finite and >= 0 m/s^2");
}

double GaussianNoise::uniform() {
  // 53 random bits -> [0, 1) exactly representable, then to (-1, 1)
  const double u = static_cast<double>(engine_() >> 11) * (1.0 / 9007199254740992.0);
  return 2.0 * u - 1.0;
}

double GaussianNoise::next() {
  if (have_spare_) {
    have_spare_ = false;
    return rms_ * spare_;
  }
  // Marsaglia's polar method: exact Gaussian pairs from uniform points in the unit disc.
  double x = 0.0;
  double y = 0.0;
  double s = 0.0;
  do {
    x = uniform();
    y = uniform();
    s = x * x + y * y;
  } while (s >= 1.0 || s == 0.0);
  const double f = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = y * f;
  have_spare_ = true;
  return rms_ * x * f;
}

}  // namespace rocking_monitor::core
