// dashboard node: a thin shim around Dashboard (see dashboard.hpp).
#include <ros/ros.h>

#include "rocking_monitor/ros/dashboard.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "dashboard");
  rocking_monitor::live::Dashboard dashboard(ros::NodeHandle(), ros::NodeHandle("~"));
  if (!dashboard.init()) return 1;
  ros::spin();  // SIGINT ends it; the destructor closes the port and every stream
  return 0;
}
