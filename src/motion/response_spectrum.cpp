#include "rocking_monitor/motion/response_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::core {

namespace {

void check_positive(double value, const char* what) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw std::invalid_argument(std::string("response spectrum: ") + what + " must be finite and > 0, got " +
                                std::to_string(value));
  }
}

void check_damping(double damping) {
  if (!(std::isfinite(damping) && damping >= 0.0 && damping < 1.0)) {
    throw std::invalid_argument("response spectrum: damping ratio must be in [0, 1), got " + std::to_string(damping));
  }
}

}  // namespace

NigamJenningsCoefficients nigam_jennings_coefficients(double period, double damping, double dt) {
  check_positive(period, "period");
  check_positive(dt, "dt");
  check_damping(damping);

  using Real = long double;
  const Real z = damping;
  const Real w = 2.0L * static_cast<Real>(kPi) / static_cast<Real>(period);
  const Real h = dt;
  const Real root = std::sqrt(1.0L - z * z);
  const Real wd = w * root;  // damped circular frequency

  const Real e = std::exp(-z * w * h);
  const Real s = std::sin(wd * h);
  const Real c = std::cos(wd * h);

  // A (N&J Eq. 2.7d): homogeneous solution over one step.
  const Real a11 = e * (z / root * s + c);
  const Real a12 = e * s / wd;
  const Real a21 = -w / root * e * s;
  const Real a22 = e * (c - z / root * s);

  // B (N&J Eq. 2.7e): response to a_g(tau) = a_i + (a_{i+1} - a_i) tau / dt, zero initial state.
  const Real k1 = (2.0L * z * z - 1.0L) / (w * w * h);  // (2 zeta^2 - 1) / (omega^2 dt)
  const Real k2 = 2.0L * z / (w * w * w * h);           // 2 zeta / (omega^3 dt)
  const Real inv_w2 = 1.0L / (w * w);
  const Real s_wd = s / wd;
  const Real c_minus = c - z / root * s;  // = a22 / e
  const Real d_term = wd * s + z * w * c;

  const Real b11 = e * ((k1 + z / w) * s_wd + (k2 + inv_w2) * c) - k2;
  const Real b12 = -e * (k1 * s_wd + k2 * c) - inv_w2 + k2;
  const Real b21 = e * ((k1 + z / w) * c_minus - (k2 + inv_w2) * d_term) + inv_w2 / h;
  const Real b22 = -e * (k1 * c_minus - k2 * d_term) - inv_w2 / h;

  NigamJenningsCoefficients out;
  out.period = period;
  out.damping = damping;
  out.dt = dt;
  out.omega = static_cast<double>(w);
  out.a11 = static_cast<double>(a11);
  out.a12 = static_cast<double>(a12);
  out.a21 = static_cast<double>(a21);
  out.a22 = static_cast<double>(a22);
  out.b11 = static_cast<double>(b11);
  out.b12 = static_cast<double>(b12);
  out.b21 = static_cast<double>(b21);
  out.b22 = static_cast<double>(b22);
  return out;
}

void oscillator_response(const std::vector<double>& accel, double dt, double period, double damping,
                         std::vector<double>& u, std::vector<double>& v) {
  NigamJenningsOscillator osc(period, damping, dt);
  const std::size_t n = accel.size();
  u.assign(n, 0.0);
  v.assign(n, 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    osc.step(accel[i], accel[i + 1]);
    u[i + 1] = osc.displacement();
    v[i + 1] = osc.velocity();
  }
}

ResponseSpectrum response_spectrum(const std::vector<double>& accel, double dt, const std::vector<double>& periods,
                                   double damping) {
  check_positive(dt, "dt");
  check_damping(damping);
  ResponseSpectrum out;
  out.damping = damping;
  out.periods = periods;
  const std::size_t m = periods.size();
  out.sd.assign(m, 0.0);
  out.sv.assign(m, 0.0);
  out.psv.assign(m, 0.0);
  out.psa.assign(m, 0.0);
  for (std::size_t j = 0; j < m; ++j) {
    NigamJenningsOscillator osc(periods[j], damping, dt);
    double max_u = 0.0;
    double max_v = 0.0;
    for (std::size_t i = 0; i + 1 < accel.size(); ++i) {
      osc.step(accel[i], accel[i + 1]);
      max_u = std::max(max_u, std::abs(osc.displacement()));
      max_v = std::max(max_v, std::abs(osc.velocity()));
    }
    const double w = osc.coefficients().omega;
    out.sd[j] = max_u;
    out.sv[j] = max_v;
    out.psv[j] = w * max_u;
    out.psa[j] = w * w * max_u;
  }
  return out;
}

ResponseSpectrum response_spectrum(const Component& component, const std::vector<double>& periods, double damping) {
  return response_spectrum(component.accel, component.dt, periods, damping);
}

std::vector<double> log_spaced_periods(double t_min, double t_max, std::size_t count) {
  check_positive(t_min, "t_min");
  check_positive(t_max, "t_max");
  if (t_max < t_min) throw std::invalid_argument("log_spaced_periods: t_max must be >= t_min");
  if (count == 0) throw std::invalid_argument("log_spaced_periods: count must be >= 1");
  std::vector<double> out(count);
  if (count == 1) {
    out[0] = t_min;
    return out;
  }
  const double log_min = std::log(t_min);
  const double step = (std::log(t_max) - log_min) / static_cast<double>(count - 1);
  for (std::size_t i = 0; i < count; ++i) out[i] = std::exp(log_min + step * static_cast<double>(i));
  out.front() = t_min;  // exact endpoints, not exp(log(x))
  out.back() = t_max;
  return out;
}

}  // namespace rocking_monitor::core
