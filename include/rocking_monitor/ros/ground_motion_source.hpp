#pragma once

// Where record_to_bag and ground_motion_player get their ground motion from (record files, a station
// of a records directory, or a synthetic YAML spec) and how they turn it into sensor_msgs/Imu
// (REP 145) and geometry_msgs/AccelStamped messages. The mapping itself is ROS-free
// (core/sensor_frame.hpp); this header adds the message filling shared by both programs.

#include <cstdint>
#include <string>
#include <vector>

#include <geometry_msgs/AccelStamped.h>
#include <ros/time.h>
#include <sensor_msgs/Imu.h>

#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/motion/sensor_frame.hpp"
#include "rocking_monitor/motion/station.hpp"

namespace rocking_monitor::records {

/// Defaults shared by record_to_bag, ground_motion_player and their docs.
inline constexpr const char* kDefaultImuTopic = "/ground/imu";
inline constexpr const char* kDefaultFrameId = "accelerometer";
/// Accelerometer white-noise density, (m/s^2)/sqrt(Hz): 25 ug/sqrt(Hz), a seismic-grade MEMS sensor
/// (ADXL355 class). Only fills linear_acceleration_covariance; no noise is added to the data.
inline constexpr double kDefaultNoiseDensity = 2.5e-4;
/// Bag stamps = this + record time: 1e9 s = 2001-09-09T01:46:40Z, a fixed, clearly synthetic epoch
/// (ros::Time(0) means "no stamp", so the record cannot start at 0).
inline constexpr std::int64_t kDefaultStartTimeNs = 1'000'000'000LL * 1'000'000'000LL;

/// The records directory configured at build time (CMake ROCKING_RECORDS_DIR, by default
/// ../shared/records next to the source tree): the default of --records-dir and ~records_dir.
std::string default_records_dir();

/// Exactly one of files / station / synthetic.
struct SourceSpec {
  std::vector<std::string> files;  ///< 1-3 record files that form one station (AT2, BBP, SMC, CSV)
  std::string station;             ///< station name/id/file name in records_dir (core::find_station)
  std::string records_dir;         ///< directory with MANIFEST.csv or records grouped by file name
  std::string synthetic;           ///< path of a synthetic-motion YAML spec (bags/README.md)
  core::ReadOptions read;          ///< CSV units
  core::SensorFrameOptions frame;  ///< azimuth, length mismatch, scale
};

/// Reads (or generates) the motion and maps it to the sensor frame. Throws std::exception whose
/// what() is one line naming the file and line (record, manifest, YAML) or the setting.
core::SensorFrameMotion load_ground_motion(const SourceSpec& spec);

/// A synthetic-motion spec (YAML):
///   description: "text"           # optional
///   rate_hz: 200                  # samples per second (> 0)
///   duration_s: 8                 # samples at 0, 1/rate, ..., duration (inclusive)
///   x_azimuth_deg: 90             # optional, documents the x direction
///   x: [ {ricker: {peak_mps2: 3, frequency_hz: 1.5, center_s: 2}} ]       # terms are summed, m/s^2
///   y: [ {gaussian_noise: {rms_mps2: 0.005, seed: 2}} ]
///   z: [ {sine_pulse: {amplitude_mps2: 1, period_s: 0.5, start_s: 1, cycles: 2}}, {constant: {value_mps2: 0.1}} ]
/// Axes left out are zeros and flagged as not recorded. z is the ground's vertical acceleration (up);
/// gravity is added when the messages are filled, as for records. Errors name "<file>:<line>".
core::SensorFrameMotion synthetic_motion_from_yaml(const std::string& path);

/// Variance (m/s^2)^2 of each accelerometer axis for white noise of density `noise_density`
/// ((m/s^2)/sqrt(Hz)) sampled every dt s, i.e. over the Nyquist band fs/2: n^2 / (2 dt).
double accel_variance(double noise_density, double dt);

/// sensor_msgs/Imu as an accelerometer-only sensor publishes it (REP 145): linear_acceleration =
/// specific force in m/s^2 (z includes +g), linear_acceleration_covariance = diag(variance);
/// orientation and angular_velocity all zeros with covariance[0] = -1 ("not provided").
sensor_msgs::Imu make_imu_message(const core::AccelerometerSample& s, const ros::Time& stamp, const std::string& frame_id,
                                  double variance);

/// geometry_msgs/AccelStamped of the ground acceleration (gravity EXCLUDED), m/s^2; angular = 0.
geometry_msgs::AccelStamped make_accel_message(const core::AccelerometerSample& s, const ros::Time& stamp,
                                               const std::string& frame_id);

/// Parses a non-negative decimal time in seconds ("1000000000", "1234.5", up to 9 decimals) into
/// nanoseconds exactly (a double cannot hold 1e9 s to the nanosecond). Throws std::invalid_argument.
std::int64_t parse_time_ns(const std::string& text);

/// One line describing the motion: samples, rate, duration and what each axis is.
std::string describe(const core::SensorFrameMotion& m);

}  // namespace rocking_monitor::records
