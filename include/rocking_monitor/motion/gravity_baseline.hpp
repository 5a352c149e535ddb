#pragma once

#include <Eigen/Core>

namespace rocking_monitor::core {

/// Removes what an accelerometer reads at rest (gravity as seen by a possibly tilted sensor, plus
/// any offset) so that only ground acceleration is left (REP 145: an Imu reports specific force,
/// i.e. +g on the up axis at rest).
///
/// Method ("tracked", the default): the baseline b starts at the first sample; afterwards, while the
/// sensor is quiet (|f - b| < quiet_threshold), b follows the reading with a first-order low-pass of
/// time constant `time_constant`; while it shakes, b is frozen. The output is f - b with b taken
/// before the update, so the result is causal. A slightly tilted or offset sensor therefore reads
/// zero at rest instead of a permanent "earthquake", and slow drift (temperature) is followed.
/// "initial" keeps the first sample for ever; "fixed" uses a given vector (e.g. exactly (0, 0, g)).
/// Start the sensor at rest: a baseline started during shaking is wrong until the shaking stops.
class GravityBaseline {
 public:
  enum class Mode { Tracked, Initial, Fixed };
  struct Config {
    Mode mode = Mode::Tracked;
    double time_constant = 60.0;    ///< s, low-pass time constant while quiet (tracked)
    double quiet_threshold = 0.05;  ///< m/s^2, |f - b| below this counts as quiet (tracked)
    Eigen::Vector3d fixed = Eigen::Vector3d(0.0, 0.0, 9.80665);  ///< m/s^2 (fixed)
  };

  GravityBaseline() = default;
  explicit GravityBaseline(const Config& config) : config_(config) { reset(); }

  void reset() {
    initialized_ = config_.mode == Mode::Fixed;
    baseline_ = config_.mode == Mode::Fixed ? config_.fixed : Eigen::Vector3d::Zero();
  }

  /// Ground acceleration (m/s^2) from one reading f (m/s^2) taken dt seconds after the previous one.
  Eigen::Vector3d remove(const Eigen::Vector3d& f, double dt) {
    if (!initialized_) {
      baseline_ = f;
      initialized_ = true;
    }
    const Eigen::Vector3d a = f - baseline_;
    if (config_.mode == Mode::Tracked && a.norm() < config_.quiet_threshold && dt > 0.0) {
      const double k = dt >= config_.time_constant ? 1.0 : dt / config_.time_constant;
      baseline_ += k * a;
    }
    return a;
  }

  /// Continues from a saved baseline (state snapshots, issue 29).
  void restore(bool initialized, const Eigen::Vector3d& baseline) {
    initialized_ = initialized;
    baseline_ = baseline;
  }

  const Eigen::Vector3d& baseline() const { return baseline_; }
  bool initialized() const { return initialized_; }
  const Config& config() const { return config_; }

 private:
  Config config_;
  bool initialized_ = false;
  Eigen::Vector3d baseline_ = Eigen::Vector3d::Zero();
};

}  // namespace rocking_monitor::core
