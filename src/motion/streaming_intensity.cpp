#include "rocking_monitor/motion/streaming_intensity.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::core {

namespace {

/// Pre-warped bilinear Butterworth coefficients shared by both filters: K = tan(pi fc dt).
struct ButterworthDenominator {
  double norm;  // 1 + sqrt(2) K + K^2
  double a1;    // 2 (K^2 - 1) / norm
  double a2;    // (1 - sqrt(2) K + K^2) / norm
};

ButterworthDenominator butterworth_denominator(double corner_hz, double dt) {
  const double k = std::tan(kPi * corner_hz * dt);
  const double sqrt2 = std::sqrt(2.0);
  const double norm = 1.0 + sqrt2 * k + k * k;
  return {norm, 2.0 * (k * k - 1.0) / norm, (1.0 - sqrt2 * k + k * k) / norm};
}

void check_corner(double corner_hz, double dt, const char* name) {
  if (!(std::isfinite(corner_hz) && corner_hz > 0.0 && corner_hz * dt < 0.5)) {
    throw std::invalid_argument(std::string("StreamingIntensity: ") + name +
                                " must be > 0 and below the Nyquist frequency, got " + std::to_string(corner_hz));
  }
}

}  // namespace

StreamingIntensity::StreamingIntensity(StreamingIntensityConfig config) : config_(std::move(config)) {
  const double dt = config_.dt;
  if (!(std::isfinite(dt) && dt > 0.0)) {
    throw std::invalid_argument("StreamingIntensity: dt must be finite and > 0, got " + std::to_string(dt));
  }
  check_corner(config_.velocity_highpass_hz, dt, "velocity_highpass_hz");
  if (config_.oscillator_highpass_hz != 0.0) check_corner(config_.oscillator_highpass_hz, dt, "oscillator_highpass_hz");

  // Velocity: bilinear image of (1/s) * s^2 / (s^2 + sqrt(2) wc s + wc^2); numerator
  // (dt/2)(1 + z^-1) * (1 - z^-1)^2 / (1 - z^-1) = (dt/2)(1 - z^-2), over the Butterworth denominator.
  const ButterworthDenominator vd = butterworth_denominator(config_.velocity_highpass_hz, dt);
  velocity_filter_.b0 = 0.5 * dt / vd.norm;
  velocity_filter_.b1 = 0.0;
  velocity_filter_.b2 = -0.5 * dt / vd.norm;
  velocity_filter_.a1 = vd.a1;
  velocity_filter_.a2 = vd.a2;

  filter_oscillators_ = config_.oscillator_highpass_hz > 0.0;
  if (filter_oscillators_) {
    const ButterworthDenominator od = butterworth_denominator(config_.oscillator_highpass_hz, dt);
    oscillator_filter_.b0 = 1.0 / od.norm;
    oscillator_filter_.b1 = -2.0 / od.norm;
    oscillator_filter_.b2 = 1.0 / od.norm;
    oscillator_filter_.a1 = od.a1;
    oscillator_filter_.a2 = od.a2;
  }

  oscillators_.reserve(config_.periods.size());
  for (double period : config_.periods) oscillators_.emplace_back(period, config_.damping, dt);  // validates
  max_u_.assign(config_.periods.size(), 0.0);
  psv_.assign(config_.periods.size(), 0.0);
}

void StreamingIntensity::reset() {
  for (auto& osc : oscillators_) osc.reset();
  for (std::size_t j = 0; j < psv_.size(); ++j) max_u_[j] = psv_[j] = 0.0;
  velocity_filter_.prime(0.0);
  oscillator_filter_.prime(0.0);
  count_ = 0;
  prev_drive_ = 0.0;
  pga_ = pga_time_ = 0.0;
  vel_ = pgv_ = pgv_time_ = 0.0;
}

void StreamingIntensity::push(double accel) {
  if (!std::isfinite(accel)) throw std::invalid_argument("StreamingIntensity::push: non-finite acceleration sample");

  if (count_ == 0) {
    velocity_filter_.prime(accel);
    oscillator_filter_.prime(accel);
  }
  const double t = config_.dt * static_cast<double>(count_);

  vel_ = velocity_filter_.step(accel);
  const double drive = filter_oscillators_ ? oscillator_filter_.step(accel) : accel;
  if (count_ > 0) {
    for (std::size_t j = 0; j < oscillators_.size(); ++j) {
      NigamJenningsOscillator& osc = oscillators_[j];
      osc.step(prev_drive_, drive);
      const double u = std::abs(osc.displacement());
      if (u > max_u_[j]) {
        max_u_[j] = u;
        psv_[j] = osc.coefficients().omega * u;
      }
    }
  }
  prev_drive_ = drive;

  if (std::abs(accel) > pga_) {
    pga_ = std::abs(accel);
    pga_time_ = t;
  }
  if (std::abs(vel_) > pgv_) {
    pgv_ = std::abs(vel_);
    pgv_time_ = t;
  }
  ++count_;
}

}  // namespace rocking_monitor::core

namespace rocking_monitor::core {

void StreamingIntensity::save(Saved& out) const {
  auto filter = [](const Biquad& b) { return FilterState{b.x1, b.x2, b.y1, b.y2}; };
  out.velocity_filter = filter(velocity_filter_);
  out.oscillator_filter = filter(oscillator_filter_);
  const std::size_t n = oscillators_.size();
  out.osc_u.resize(n);
  out.osc_v.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    out.osc_u[j] = oscillators_[j].displacement();
    out.osc_v[j] = oscillators_[j].velocity();
  }
  out.max_u.assign(max_u_.begin(), max_u_.end());
  out.count = count_;
  out.prev_drive = prev_drive_;
  out.pga = pga_;
  out.pga_time = pga_time_;
  out.vel = vel_;
  out.pgv = pgv_;
  out.pgv_time = pgv_time_;
}

void StreamingIntensity::restore(const Saved& in) {
  const std::size_t n = oscillators_.size();
  if (in.osc_u.size() != n || in.osc_v.size() != n || in.max_u.size() != n)
    throw std::invalid_argument("StreamingIntensity::restore: " + std::to_string(in.osc_u.size()) +
                                " oscillator periods saved, this instance has " + std::to_string(n));
  auto filter = [](Biquad& b, const FilterState& f) {
    b.x1 = f.x1;
    b.x2 = f.x2;
    b.y1 = f.y1;
    b.y2 = f.y2;
  };
  filter(velocity_filter_, in.velocity_filter);
  filter(oscillator_filter_, in.oscillator_filter);
  for (std::size_t j = 0; j < n; ++j) {
    oscillators_[j].restore(in.osc_u[j], in.osc_v[j]);
    max_u_[j] = in.max_u[j];
    psv_[j] = oscillators_[j].coefficients().omega * max_u_[j];
  }
  count_ = in.count;
  prev_drive_ = in.prev_drive;
  pga_ = in.pga;
  pga_time_ = in.pga_time;
  vel_ = in.vel;
  pgv_ = in.pgv;
  pgv_time_ = in.pgv_time;
}

void StreamingIntensity::to_lane(Lane& l) const {
  l.velocity = velocity_filter_;
  l.osc = oscillators_[0];
  l.prev_drive = prev_drive_;
  l.vel = vel_;
  l.pga = pga_;
  l.pgv = pgv_;
  l.max_u = max_u_[0];
  l.count = count_;
}

void StreamingIntensity::from_lane(const Lane& l) {
  velocity_filter_ = l.velocity;
  oscillators_[0] = l.osc;
  prev_drive_ = l.prev_drive;
  vel_ = l.vel;
  count_ = l.count;  // maxima and their times are unchanged by quiet samples
}

bool StreamingIntensity::push_quiet(Lane& l, double accel) {
  // push() with drive = accel (no pre-filter), on copies: the same filter and oscillator code.
  Biquad velocity = l.velocity;
  NigamJenningsOscillator osc = l.osc;
  const double y = velocity.step(accel);
  osc.step(l.prev_drive, accel);
  if (std::abs(osc.displacement()) > l.max_u || std::abs(accel) > l.pga || std::abs(y) > l.pgv) return false;
  l.velocity = velocity;
  l.osc = osc;
  l.prev_drive = accel;
  l.vel = y;
  ++l.count;
  return true;
}

}  // namespace rocking_monitor::core
