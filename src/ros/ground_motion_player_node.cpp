// ground_motion_player node: streams a strong-motion record live as sensor_msgs/Imu (REP 145).
// Parameters and topics: include/rocking_monitor/ros/ground_motion_player.hpp, launch/player.launch,
// docs/records.md. Bad parameters or input: one ROS_FATAL line, exit status 2.

#include <ros/ros.h>

#include <exception>
#include <string>

#include "rocking_monitor/ros/ground_motion_player.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "ground_motion_player");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  namespace rec = rocking_monitor::records;
  rec::PlayerConfig config;
  rocking_monitor::core::SensorFrameMotion motion;
  try {
    config = rec::read_player_config(pnh);
    motion = rec::load_ground_motion(config.source);
  } catch (const std::exception& e) {
    std::string what = e.what();
    for (char& c : what) c = c == '\n' ? ' ' : c;
    ROS_FATAL("ground_motion_player: %s", what.c_str());
    return 2;
  }
  ros::AsyncSpinner spinner(1);  // connection callbacks while run() blocks
  spinner.start();
  rec::GroundMotionPlayer player(nh, pnh, config, std::move(motion));
  player.run();  // an interruption (Ctrl-C) is logged with the count of samples played; not an error
  ros::shutdown();
  return 0;
}
