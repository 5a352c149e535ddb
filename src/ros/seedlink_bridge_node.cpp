// seedlink_bridge node: a thin shim around SeedLinkBridge (see seedlink_bridge.hpp).
#include <ros/ros.h>

#include "rocking_monitor/ros/seedlink_bridge.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "seedlink_bridge");
  rocking_monitor::live::SeedLinkBridge bridge(ros::NodeHandle(), ros::NodeHandle("~"));
  if (!bridge.init()) return 1;
  ros::spin();
  return 0;
}
