#pragma once
// record_to_bag's output: the bag (sensor_msgs/Imu, optionally geometry_msgs/AccelStamped) of a
// station's ground motion in the sensor frame, its CSV, and the reader's notes.

#include <rosbag/bag.h>

#include <cstdint>
#include <string>

#include "rocking_monitor/motion/sensor_frame.hpp"
#include "rocking_monitor/ros/ground_motion_source.hpp"

namespace rocking_monitor::tools::record_to_bag {

namespace core = rocking_monitor::core;
namespace rec = rocking_monitor::records;

constexpr const char* kProgram = "record_to_bag";

struct BagOptions {
  std::string topic = rec::kDefaultImuTopic;
  std::string accel_topic;  // empty: no AccelStamped
  std::string frame_id = rec::kDefaultFrameId;
  std::int64_t start_ns = rec::kDefaultStartTimeNs;
  double noise_density = rec::kDefaultNoiseDensity;
  rosbag::compression::CompressionType compression = rosbag::compression::LZ4;
};

struct BagStats {
  std::size_t messages = 0;
  std::uintmax_t bytes = 0;
};

/// Writes the bag to "<out>.partial" and renames it at the end, so a failure never leaves a
/// truncated bag under the final name.
BagStats write_bag(const core::SensorFrameMotion& m, const std::string& out, const BagOptions& o);

/// The notes of reading the record (padding, rotation, ...) on stderr, each after prefix.
void print_notes(const core::SensorFrameMotion& m, const std::string& prefix = "");

/// --csv-out: the ground acceleration on the sensor axes (time_s,x,y,z in m/s^2).
void write_csv(const core::SensorFrameMotion& m, const std::string& path);

}  // namespace rocking_monitor::tools::record_to_bag
