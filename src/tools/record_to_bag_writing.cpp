// record_to_bag's output: the bag, the CSV and the notes.
#include "record_to_bag_writing.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace rocking_monitor::tools::record_to_bag {

BagStats write_bag(const core::SensorFrameMotion& m, const std::string& out, const BagOptions& o) {
  if (m.size() == 0) throw std::runtime_error(out + ": nothing to write (no samples)");
  const std::int64_t first = o.start_ns + m.time_ns(0);
  const std::int64_t last = o.start_ns + m.time_ns(m.size() - 1);
  if (first <= 0) throw std::invalid_argument("--start-time: the first stamp would be <= 0 s (record starts at t0 = " + std::to_string(m.t0) + " s)");
  if (last / 1'000'000'000LL > 4294967295LL) throw std::invalid_argument("--start-time: the last stamp is beyond the range of ros::Time");
  const double variance = rec::accel_variance(o.noise_density, m.dt);
  const std::string tmp = out + ".partial";
  BagStats stats;
  try {
    rosbag::Bag bag;
    bag.open(tmp, rosbag::bagmode::Write);
    bag.setCompression(o.compression);
    for (std::size_t i = 0; i < m.size(); ++i) {
      const core::AccelerometerSample s = m.sample(i);
      ros::Time stamp;
      stamp.fromNSec(static_cast<std::uint64_t>(o.start_ns + s.time_ns));
      bag.write(o.topic, stamp, rec::make_imu_message(s, stamp, o.frame_id, variance));
      ++stats.messages;
      if (!o.accel_topic.empty()) {
        bag.write(o.accel_topic, stamp, rec::make_accel_message(s, stamp, o.frame_id));
        ++stats.messages;
      }
    }
    bag.close();
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, out);
  stats.bytes = fs::file_size(out);
  return stats;
}

void print_notes(const core::SensorFrameMotion& m, const std::string& prefix) {
  for (const std::string& n : m.notes) std::cerr << kProgram << ": note: " << prefix << n << "\n";
}

void write_csv(const core::SensorFrameMotion& m, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing (--csv-out)");
  out << "# ground acceleration on the sensor axes (gravity excluded), m/s^2; " << rec::describe(m) << "\n";
  out << "time_s,x_mps2,y_mps2,z_mps2\n";
  char line[160];
  for (std::size_t i = 0; i < m.size(); ++i) {
    std::snprintf(line, sizeof line, "%.9f,%.17g,%.17g,%.17g\n", static_cast<double>(m.time_ns(i)) * 1e-9, m.ground[0][i],
                  m.ground[1][i], m.ground[2][i]);
    out << line;
  }
  if (!out) throw std::runtime_error(path + ": write failed (--csv-out)");
}

}  // namespace rocking_monitor::tools::record_to_bag
