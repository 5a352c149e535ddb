#!/usr/bin/python3
"""Prints a live per-item table of rocking_monitor states and, at shutdown, the alarm summary.

Times are seconds since the first sample of the sensor (~imu; without it, since the first state
received; alarms carry the monitor's own count) with the UTC wall time of the stamp, as in the
monitor's own log lines. Each item shows its worse rocking plane ("y/2": plane y of two). With ~end_after_idle > 0 the table ends by itself (exit status 0) once states have stopped
coming for that many wall-clock seconds: the end of a replayed record (scripts/run_demo.sh).
With ~pair (the other monitor of a redundant pair, launch/monitor_pair.launch, e.g. /rocking_monitor_b) its
alarms are listed too, each alarm once (scripts/alarm_dedup.py, docs/journal.md "A redundant pair")."""
import datetime
import os
import sys
import threading
import time

import rospy
from rocking_monitor.msg import RockingStateArray, OverturnAlarm
from sensor_msgs.msg import Imu

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))  # alarm_dedup.py beside this file
from alarm_dedup import AlarmDedup  # noqa: E402

MODES = {0: "REST", 1: "ROCKING", 2: "BEYOND_TIPPING", 3: "COMMITTED", 4: "OVERTURNED"}
LEVELS = {2: "BEYOND_TIPPING", 3: "COMMITTED", 4: "OVERTURNED"}


class Table:
    def __init__(self):
        self.period = rospy.get_param("~period", 1.0)  # s between tables
        self.latest = None
        self.alarms = AlarmDedup()  # each alarm once: re-sent after a restart, or from the pair's other monitor
        self.alarms_lock = threading.Lock()  # rospy calls each subscription's callback on its own thread
        self.last_print = None
        self.t0 = None  # stamp of the first sample (else of the first state): times are relative to it
        self.t0_is_sample = False
        self.end_after_idle = rospy.get_param("~end_after_idle", 0.0)  # wall s; 0 = run until shut down
        self.last_state_wall = None
        rospy.Subscriber(rospy.get_param("~states", "/rocking_monitor/states"), RockingStateArray, self.on_states)
        alarms = rospy.get_param("~alarms", "/rocking_monitor/alarms")
        rospy.Subscriber(alarms, OverturnAlarm, lambda m: self.on_alarm(alarms, m), queue_size=1000)
        pair = rospy.get_param("~pair", "").rstrip("/")
        if pair:
            pair_alarms = pair + "/alarms"
            if pair_alarms == alarms:
                raise SystemExit("monitor_table: ~pair %s is the monitor itself (~alarms %s)" % (pair, alarms))
            rospy.Subscriber(pair_alarms, OverturnAlarm, lambda m: self.on_alarm(pair_alarms, m), queue_size=1000)
        imu = rospy.get_param("~imu", "/ground/imu")
        if imu:
            self.imu_sub = rospy.Subscriber(imu, Imu, self.on_imu, queue_size=10)
        rospy.on_shutdown(self.summary)

    def on_imu(self, msg):
        if not self.t0_is_sample and not msg.header.stamp.is_zero():
            self.t0 = msg.header.stamp.to_sec()
            self.t0_is_sample = True
            self.imu_sub.unregister()  # only the first sample is needed

    def on_states(self, msg):
        self.latest = msg
        self.last_state_wall = time.monotonic()
        if self.t0 is None and not msg.header.stamp.is_zero():
            self.t0 = msg.header.stamp.to_sec()
        now = rospy.get_time()
        if self.last_print is None or now - self.last_print >= self.period:
            self.last_print = now
            self.print_table(msg)

    def on_alarm(self, source, msg):
        with self.alarms_lock:
            self.alarms.add(source, msg)

    def rel(self, t):
        return t - self.t0 if self.t0 is not None else t

    @staticmethod
    def utc(t):
        """ISO 8601 UTC of a stamp, to the millisecond (as the monitor's log lines)."""
        ms = round(t * 1000.0)
        when = datetime.datetime(1970, 1, 1) + datetime.timedelta(milliseconds=ms)
        return when.strftime("%Y-%m-%dT%H:%M:%S.") + "%03dZ" % (ms % 1000)

    def idle(self):
        """True once states came and then stopped for ~end_after_idle wall-clock seconds."""
        return (self.end_after_idle > 0.0 and self.last_state_wall is not None and
                time.monotonic() - self.last_state_wall > self.end_after_idle)

    def print_table(self, msg):
        stamp = msg.header.stamp.to_sec()
        since = "the first sample" if self.t0_is_sample else "the first state"
        lines = ["", "t = %.2f s since %s (%s)" % (self.rel(stamp), since, self.utc(stamp)),
                 "%-18s %-15s %-5s %8s %9s %8s %7s %8s %s" % (
                     "item", "state", "plane", "theta", "|th|/alp", "margin", "impacts", "slip_mm", "model")]
        for s in msg.items:
            # The item's fields are those of its worse plane; "x/2" = plane x of an item with two planes.
            plane = "%s/%d" % (s.plane or "x", s.plane_count or 1)
            model = s.model if s.model_valid else "%s, violated (%d)" % (s.model, s.violations)
            lines.append("%-18s %-15s %-5s %8.4f %9.3f %8.3f %7d %8.1f %s" % (
                s.id, MODES.get(s.mode, "?"), plane, s.theta, s.rotation_ratio, s.energy_margin, s.impacts,
                1000.0 * s.slip, model))
        print("\n".join(lines), flush=True)

    def summary(self):
        if self.latest is not None:
            self.print_table(self.latest)
        with self.alarms_lock:
            alarms = self.alarms.alarms()
        print("\nAlarm summary (%d alarms; copies not listed: %d from the pair's other monitor, %d received again):"
              % (len(alarms), self.alarms.merged, self.alarms.repeats))
        for a in alarms:
            # OverturnAlarm.cause 1 (issue 51): it slid off its plinth, shelf or pedestal
            fell_off = " (fell off its support)" if getattr(a, "cause", 0) == 1 else ""
            print("  t = %8.3f s  %s  %-15s %-18s plane %s%s  predicted by: %s; not by: %s" % (
                a.time_since_first_sample, self.utc(a.event_time), LEVELS.get(a.level, "?"), a.item_id, a.plane, fell_off,
                ", ".join(a.predicted_by) or "none",
                ", ".join(a.not_predicted_by) or "none"), flush=True)
        if not alarms:
            print("  none: every item stayed within its tipping angle", flush=True)


if __name__ == "__main__":
    rospy.init_node("monitor_table")
    table = Table()
    while not rospy.is_shutdown():
        if table.idle():
            rospy.signal_shutdown("no states for %.1f s: the record has ended" % table.end_after_idle)
            break
        time.sleep(0.2)  # wall clock: under sim time /clock stops with the bag
