#pragma once

// Linear single-degree-of-freedom oscillator response and response spectra.
//
// Why: the response spectrum (Sd, PSV, PSA versus period) says how strongly a record drives
// structures and contents of each natural period; it is the standard way to compare records
// and to relate the monitor's readings to design spectra.
//
// Method: Nigam, N. C. & Jennings, P. C. (1969), "Calculation of response spectra from strong-motion
// earthquake records", Bull. Seism. Soc. Am. 59(2), 909-922 (also the 1968 EERL Caltech report).
// With the ground acceleration taken as linear between samples, the oscillator equation
//     u'' + 2 zeta omega u' + omega^2 u = -a_g(t)      (u = displacement relative to the ground)
// has a closed-form solution over each interval, giving the exact recurrence
//     [u_{i+1}; v_{i+1}] = A [u_i; v_i] + B [a_i; a_{i+1}].
// It is exact for any dt (no stability limit, no period elongation); the only approximation is the
// piecewise-linear interpolation of the record itself. Coefficients follow N&J Eq. 2.7d/2.7e as coded
// in eqsig (eng-tools/eqsig, eqsig/sdof.py, compute_a_and_b) and in Dreger's widely copied "cmpmax"
// Fortran routine (e.g. elygeo/coseis extras/rspectra.f90); they are verified in the tests against
// closed-form step and ramp responses.
//
// Units: periods s, damping ratio (fraction of critical), acceleration m/s^2, Sd m, Sv and PSV m/s, PSA m/s^2.

#include <cstddef>
#include <vector>

#include "rocking_monitor/motion/component.hpp"

namespace rocking_monitor::core {

/// Damping ratio conventionally used for response spectra (5 % of critical).
inline constexpr double kDefaultSpectralDamping = 0.05;

/// The Nigam-Jennings recurrence coefficients for one (period, damping, dt).
struct NigamJenningsCoefficients {
  double period = 0.0;   ///< s
  double damping = 0.0;  ///< fraction of critical
  double dt = 0.0;       ///< s
  double omega = 0.0;    ///< 2 pi / period, rad/s
  double a11 = 0.0, a12 = 0.0, a21 = 0.0, a22 = 0.0;  ///< A: free-vibration transition over dt
  double b11 = 0.0, b12 = 0.0, b21 = 0.0, b22 = 0.0;  ///< B: weights of a_i and a_{i+1}
};

/// Computes A and B. Evaluated in long double: B contains terms ~2 zeta/(omega^3 dt) that cancel to a
/// result ~dt^2, which in double would lose ~(omega dt)^-3 of precision for long periods and small dt.
/// Throws std::invalid_argument unless period > 0, 0 <= damping < 1 and dt > 0 (all finite).
NigamJenningsCoefficients nigam_jennings_coefficients(double period, double damping, double dt);

/// One oscillator, starting at rest, advanced one sample interval at a time. Coefficients are computed
/// once at construction; step() does 8 multiply-adds and never allocates (used by the streaming monitor).
class NigamJenningsOscillator {
 public:
  NigamJenningsOscillator() = default;
  NigamJenningsOscillator(double period, double damping, double dt)
      : c_(nigam_jennings_coefficients(period, damping, dt)) {}

  /// Advances from the sample with ground acceleration a_prev to the next one with a_next (m/s^2).
  void step(double a_prev, double a_next) {
    const double u = c_.a11 * u_ + c_.a12 * v_ + c_.b11 * a_prev + c_.b12 * a_next;
    const double v = c_.a21 * u_ + c_.a22 * v_ + c_.b21 * a_prev + c_.b22 * a_next;
    u_ = u;
    v_ = v;
  }
  void reset() { u_ = v_ = 0.0; }
  /// Puts the oscillator in a saved state (u m, v m/s; state snapshots).
  void restore(double u, double v) {
    u_ = u;
    v_ = v;
  }

  double displacement() const { return u_; }  ///< relative displacement u, m
  double velocity() const { return v_; }      ///< relative velocity u', m/s
  const NigamJenningsCoefficients& coefficients() const { return c_; }

 private:
  NigamJenningsCoefficients c_{};
  double u_ = 0.0;
  double v_ = 0.0;
};

/// Relative displacement u (m) and velocity v (m/s) histories of one oscillator, at rest at the first
/// sample; u and v are resized to accel.size().
void oscillator_response(const std::vector<double>& accel, double dt, double period, double damping,
                         std::vector<double>& u, std::vector<double>& v);

/// Spectral ordinates on a period grid. Maxima are taken over the samples (not between them), which
/// can underestimate a peak falling between two samples by up to 1 - cos(pi dt / T) (worst case for a
/// harmonic response): 0.5 % at dt = T/30, 5 % at dt = T/10. Resample finer if short periods matter.
struct ResponseSpectrum {
  double damping = kDefaultSpectralDamping;
  std::vector<double> periods;  ///< s
  std::vector<double> sd;       ///< max |u|, m
  std::vector<double> sv;       ///< max |u'| (true relative velocity, not pseudo), m/s
  std::vector<double> psv;      ///< omega * sd, m/s
  std::vector<double> psa;      ///< omega^2 * sd, m/s^2
};

/// Response spectrum of a whole record (acceleration as given: baseline-correct it first if needed).
/// Each oscillator starts at rest at the first sample. Coefficients are computed once per period.
/// Throws std::invalid_argument for invalid periods (must be > 0), damping or dt.
ResponseSpectrum response_spectrum(const std::vector<double>& accel, double dt, const std::vector<double>& periods,
                                   double damping = kDefaultSpectralDamping);

ResponseSpectrum response_spectrum(const Component& component, const std::vector<double>& periods,
                                   double damping = kDefaultSpectralDamping);

/// `count` periods spaced evenly in log(period) from t_min to t_max inclusive (default 0.02-10 s).
/// count == 1 gives {t_min}. Throws std::invalid_argument unless 0 < t_min <= t_max and count >= 1.
std::vector<double> log_spaced_periods(double t_min = 0.02, double t_max = 10.0, std::size_t count = 100);

}  // namespace rocking_monitor::core
