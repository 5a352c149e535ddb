// alarm_notifier node: a thin shim around AlarmNotifier (see alarm_notifier.hpp, docs/notify.md).
#include <ros/ros.h>

#include "rocking_monitor/ros/alarm_notifier.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "alarm_notifier");
  rocking_monitor::live::AlarmNotifier notifier(ros::NodeHandle(), ros::NodeHandle("~"));
  if (!notifier.init()) return 2;
  // Two threads: a delivery never waits for a burst of alarms being accepted, nor the reverse.
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ros::waitForShutdown();
  return 0;
}
