// udp_accel_bridge node: a thin shim around UdpAccelBridge (see udp_accel_bridge.hpp).
#include <ros/ros.h>

#include "rocking_monitor/ros/udp_accel_bridge.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "udp_accel_bridge");
  rocking_monitor::live::UdpAccelBridge bridge(ros::NodeHandle(), ros::NodeHandle("~"));
  if (!bridge.init()) return 2;
  ros::spin();
  return 0;
}
