// rocking_monitor node: a thin shim around RockingMonitor (see monitor.hpp).
#include <ros/ros.h>

#include "rocking_monitor/ros/monitor.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "rocking_monitor");
  rocking_monitor::live::RockingMonitor monitor(ros::NodeHandle(), ros::NodeHandle("~"));
  if (!monitor.init()) return 1;
  ros::spin();
  return 0;
}
