#pragma once
// A test's /diagnostics subscriber proven connected before the test relies on one publication (issue 42).
// Under use_sim_time the monitor's diagnostic_updater publishes once per second of the node's clock:
// a clock jump brings one publication, and a clock held there brings no other. On a loaded machine
// that one can go out before the subscriber's connection is up (monitor_faults at load 13: "the
// monitor never showed the clock"). So before the first jump, the clock is stepped by more than the
// period until a message has arrived; from then on the connection is up and every one is received.

#include <functional>

#include <ros/ros.h>

namespace rocking_monitor::test {

// Steps publish_clock from `from` by 1.1 s every 0.5 s of wall time until received(); false if
// nothing came within give_up_s. The clock ends at most 1.1 * give_up_s / 0.5 s past `from` (66 s
// for 30 s): callers start far enough before the times they test.
inline bool step_clock_until_diagnostics(const std::function<void(const ros::Time&)>& publish_clock,
                                         const std::function<bool()>& received, ros::Time from,
                                         double give_up_s = 30.0) {
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(give_up_s);
  while (!received() && ros::WallTime::now() < give_up) {
    from += ros::Duration(1.1);
    publish_clock(from);
    const ros::WallTime next = ros::WallTime::now() + ros::WallDuration(0.5);
    while (!received() && ros::WallTime::now() < next) {
      ros::spinOnce();
      ros::WallDuration(0.005).sleep();
    }
  }
  return received();
}

}  // namespace rocking_monitor::test
