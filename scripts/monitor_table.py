#!/usr/bin/python3
"""Prints a live per-item table of rocking_monitor states and, at shutdown, the alarm summary."""
import rospy
from rocking_monitor.msg import RockingStateArray, OverturnAlarm

MODES = {0: "REST", 1: "ROCKING", 2: "BEYOND_TIPPING", 3: "COMMITTED", 4: "OVERTURNED"}
LEVELS = {2: "BEYOND_TIPPING", 3: "COMMITTED", 4: "OVERTURNED"}


class Table:
    def __init__(self):
        self.period = rospy.get_param("~period", 1.0)  # s between tables
        self.latest = None
        self.alarms = []
        self.last_print = None
        self.t0 = None  # input stamp of the first state received: times are printed relative to it
        rospy.Subscriber(rospy.get_param("~states", "/rocking_monitor/states"), RockingStateArray, self.on_states)
        rospy.Subscriber(rospy.get_param("~alarms", "/rocking_monitor/alarms"), OverturnAlarm, self.on_alarm,
                         queue_size=1000)
        rospy.on_shutdown(self.summary)

    def on_states(self, msg):
        self.latest = msg
        if self.t0 is None and not msg.header.stamp.is_zero():
            self.t0 = msg.header.stamp.to_sec()
        now = rospy.get_time()
        if self.last_print is None or now - self.last_print >= self.period:
            self.last_print = now
            self.print_table(msg)

    def on_alarm(self, msg):
        self.alarms.append(msg)

    def rel(self, t):
        return t - self.t0 if self.t0 is not None else t

    def print_table(self, msg):
        lines = ["", "t = %.2f s (input time since the first state received)" % self.rel(msg.header.stamp.to_sec()),
                 "%-18s %-15s %8s %9s %8s %7s %s" % ("item", "state", "theta", "|th|/alp", "margin", "impacts", "model")]
        for s in msg.items:
            lines.append("%-18s %-15s %8.4f %9.3f %8.3f %7d %s" % (
                s.id, MODES.get(s.mode, "?"), s.theta, s.rotation_ratio, s.energy_margin, s.impacts,
                "ok" if s.model_valid else "violated (%d)" % s.violations))
        print("\n".join(lines), flush=True)

    def summary(self):
        if self.latest is not None:
            self.print_table(self.latest)
        print("\nAlarm summary (%d alarms):" % len(self.alarms))
        for a in self.alarms:
            print("  t = %8.3f s  %-15s %-18s predicted by: %s; not by: %s" % (
                self.rel(a.event_time), LEVELS.get(a.level, "?"), a.item_id, ", ".join(a.predicted_by) or "none",
                ", ".join(a.not_predicted_by) or "none"), flush=True)
        if not self.alarms:
            print("  none: every item stayed within its tipping angle", flush=True)


if __name__ == "__main__":
    rospy.init_node("monitor_table")
    Table()
    rospy.spin()
