#include "rocking_monitor/motion/ground_motion_integration.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

namespace rocking_monitor::core {

namespace {

constexpr int kMaxPolyOrder = 10;

void check_dt(double dt) {
  if (!(std::isfinite(dt) && dt > 0.0)) {
    throw std::invalid_argument("ground motion integration: dt must be finite and > 0, got " + std::to_string(dt));
  }
}

Eigen::Map<const Eigen::VectorXd> as_eigen(const std::vector<double>& y) {
  return Eigen::Map<const Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
}

}  // namespace

std::vector<double> polynomial_trend(const std::vector<double>& y, int order) {
  if (order < 0 || order > kMaxPolyOrder) {
    throw std::invalid_argument("polynomial_trend: order must be in [0, 10], got " + std::to_string(order));
  }
  const std::size_t n = y.size();
  if (n == 0) return {};
  const int degree = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(order), n - 1));

  // Legendre polynomials of x in [-1, 1]: the same span as monomials, far better conditioned.
  const Eigen::Index rows = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd basis(rows, degree + 1);
  for (Eigen::Index i = 0; i < rows; ++i) {
    const double x = n > 1 ? 2.0 * static_cast<double>(i) / static_cast<double>(n - 1) - 1.0 : 0.0;
    basis(i, 0) = 1.0;
    if (degree >= 1) basis(i, 1) = x;
    for (int k = 2; k <= degree; ++k) {  // k P_k = (2k-1) x P_{k-1} - (k-1) P_{k-2}
      basis(i, k) = ((2.0 * k - 1.0) * x * basis(i, k - 1) - (k - 1.0) * basis(i, k - 2)) / k;
    }
  }
  const Eigen::VectorXd coeffs = basis.colPivHouseholderQr().solve(as_eigen(y));
  const Eigen::VectorXd fit = basis * coeffs;
  return std::vector<double>(fit.data(), fit.data() + fit.size());
}

void remove_polynomial_trend(std::vector<double>& y, int order) {
  const std::vector<double> trend = polynomial_trend(y, order);
  for (std::size_t i = 0; i < y.size(); ++i) y[i] -= trend[i];
}

void integrate_acceleration(const std::vector<double>& accel, double dt, std::vector<double>& vel,
                            std::vector<double>& disp) {
  check_dt(dt);
  const std::size_t n = accel.size();
  vel.assign(n, 0.0);
  disp.assign(n, 0.0);
  const double half_dt = 0.5 * dt;
  const double dt2_6 = dt * dt / 6.0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    vel[i + 1] = vel[i] + half_dt * (accel[i] + accel[i + 1]);
    disp[i + 1] = disp[i] + dt * vel[i] + dt2_6 * (2.0 * accel[i] + accel[i + 1]);
  }
}

std::vector<double> displacement_fit_acceleration(const std::vector<double>& disp, double dt, int order) {
  check_dt(dt);
  if (order < 2 || order > kMaxPolyOrder) {
    throw std::invalid_argument("displacement_fit_acceleration: order must be in [2, 10], got " +
                                std::to_string(order));
  }
  const std::size_t n = disp.size();
  std::vector<double> correction(n, 0.0);
  // Unknowns c2..cN; the first row (t = 0) carries no information, so n - 1 rows remain.
  const int top = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(order), n));
  if (n < 2 || top < 2) return correction;
  const int unknowns = top - 1;

  // Fit in tau = t / T in [0, 1] (T = record length) to keep the columns of comparable size.
  const double length = dt * static_cast<double>(n - 1);
  const Eigen::Index rows = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd basis(rows, unknowns);
  for (Eigen::Index i = 0; i < rows; ++i) {
    const double tau = static_cast<double>(i) / static_cast<double>(n - 1);
    double p = tau * tau;
    for (int k = 0; k < unknowns; ++k) {
      basis(i, k) = p;
      p *= tau;
    }
  }
  const Eigen::VectorXd c = basis.colPivHouseholderQr().solve(as_eigen(disp));

  // d2/dt2 sum_k c_k tau^k = sum_k k (k-1) c_k tau^(k-2) / T^2.
  const double inv_len2 = 1.0 / (length * length);
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = static_cast<double>(i) / static_cast<double>(n - 1);
    double p = 1.0;
    double sum = 0.0;
    for (int k = 0; k < unknowns; ++k) {
      const double power = k + 2.0;
      sum += power * (power - 1.0) * c(k) * p;
      p *= tau;
    }
    correction[i] = sum * inv_len2;
  }
  return correction;
}

GroundMotionHistories integrate_ground_motion(const std::vector<double>& accel, double dt,
                                              const BaselineOptions& options, double t0) {
  check_dt(dt);
  if (options.accel_poly_order > kMaxPolyOrder) {
    throw std::invalid_argument("BaselineOptions::accel_poly_order must be <= 10");
  }
  if (options.disp_poly_order != 0 && (options.disp_poly_order < 2 || options.disp_poly_order > kMaxPolyOrder)) {
    throw std::invalid_argument("BaselineOptions::disp_poly_order must be 0 (off) or in [2, 10]");
  }
  GroundMotionHistories out;
  out.dt = dt;
  out.t0 = t0;
  out.accel = accel;
  if (options.accel_poly_order >= 0) remove_polynomial_trend(out.accel, options.accel_poly_order);
  integrate_acceleration(out.accel, dt, out.vel, out.disp);
  if (options.disp_poly_order >= 2) {
    const std::vector<double> correction = displacement_fit_acceleration(out.disp, dt, options.disp_poly_order);
    for (std::size_t i = 0; i < out.accel.size(); ++i) out.accel[i] -= correction[i];
    integrate_acceleration(out.accel, dt, out.vel, out.disp);
  }
  return out;
}

GroundMotionHistories integrate_ground_motion(const Component& component, const BaselineOptions& options) {
  return integrate_ground_motion(component.accel, component.dt, options, component.t0);
}

}  // namespace rocking_monitor::core
