"""event_report.recorder: rocking_report --node: keeps the last ~pre_event seconds of the monitor's topics,
detects an event and its end, and writes the event's bag and report."""
import collections
import json
import os
import sys
import threading
import time

from .common import CAUGHT_UP, ReportError
from .html_page import utc
from .report_file import write_report


class EventRecorder:
    """Keeps the last ~pre_event seconds of the monitor's topics and its input; on an event's end writes
    them to a bag and the report next to it (on its own thread: callbacks only append)."""

    def __init__(self):
        import rospy
        from diagnostic_msgs.msg import DiagnosticArray
        from geometry_msgs.msg import AccelStamped
        from sensor_msgs.msg import Imu
        from rocking_monitor.msg import CriterionExceedance, OverturnAlarm, RockingStateArray
        self.dir = rospy.get_param('~report_dir', '')
        self.monitor = rospy.get_param('~monitor', '/rocking_monitor').rstrip('/')
        # A redundant pair (launch/monitor_pair.launch): the other monitor's alarms too, each alarm once.
        self.pair = rospy.get_param('~pair', '').rstrip('/') or None
        if self.pair and (not self.pair.startswith('/') or self.pair == self.monitor):
            rospy.logfatal('rocking_report: ~pair = %s must be the absolute namespace of the other monitor of the '
                           'pair (not ~monitor %s), e.g. /rocking_monitor_b', self.pair, self.monitor)
            sys.exit(1)
        self.pre_event = float(rospy.get_param('~pre_event', 10.0))
        self.quiet_time = float(rospy.get_param('~quiet_time', 5.0))
        self.idle_timeout = float(rospy.get_param('~idle_timeout', 3.0))
        # The monitor's alarm journal (its ~journal; default as the monitor's), read into each report.
        home = os.environ.get('ROS_HOME') or os.path.join(os.path.expanduser('~'), '.ros')
        self.journal = rospy.get_param('~journal', rospy.get_param(
            self.monitor + '/journal', os.path.join(home, 'rocking_monitor', 'journal.jsonl')))
        if not self.dir:
            rospy.logfatal('rocking_report: ~report_dir is empty: nothing to do (set it to write reports)')
            sys.exit(1)
        os.makedirs(self.dir, exist_ok=True)
        self.lock = threading.Lock()
        self.buffer = collections.deque()  # (topic, msg, receive time)
        self.in_event = False
        self.quiet_since = None
        self.last_input_wall = None
        # Wall time at which the monitor's states last reflected a newer input sample: a monitor still
        # working through queued samples is not idle, even when the sensor has stopped.
        self.last_states_stamp, self.last_progress_wall = 0.0, None
        self.ended_stamp = 0.0  # newest input stamp of the last event: later states must be newer to open one
        self.last_input_stamp = 0.0
        self.reports = 0
        subs = [(self.monitor + '/states', RockingStateArray, self.on_states),
                (self.monitor + '/alarms', OverturnAlarm, self.on_alarm),
                (self.monitor + '/criteria', CriterionExceedance, None), ('/diagnostics', DiagnosticArray, None)]
        if self.pair:
            subs.append((self.pair + '/alarms', OverturnAlarm, self.on_alarm))
        for s in rospy.get_param(self.monitor + '/sensors', []):
            subs.append((rospy.resolve_name(s['topic']), Imu if s.get('type', 'imu') == 'imu' else AccelStamped, self.on_input))
        self.inputs = set(t for t, _, cb in subs if cb == self.on_input)
        self.subs = [rospy.Subscriber(t, T, self.make_cb(t, cb), queue_size=1000) for t, T, cb in subs]
        self.thread = threading.Thread(target=self.watch, daemon=True)
        self.thread.start()
        rospy.loginfo('rocking_report: writing a report into %s after each event of %s', self.dir, self.monitor)

    def make_cb(self, topic, extra):
        import rospy
        def cb(msg):
            received = rospy.Time.now()
            if received.is_zero() and hasattr(msg, 'header'):
                # Sim time whose first /clock has not reached this node yet (a bag played with --clock
                # sends both at once): the message's own stamp, not 0, which the pre-event window
                # below would take for 30 years ago and drop (the pulse's first samples were lost).
                received = msg.header.stamp
            with self.lock:
                self.buffer.append((topic, msg, received))
                if extra:
                    extra(msg)
                if not self.in_event:  # keep only the pre-event window
                    while self.buffer and (self.buffer[-1][2] - self.buffer[0][2]).to_sec() > self.pre_event:
                        self.buffer.popleft()
        return cb

    def on_input(self, msg):
        self.last_input_wall = time.time()
        self.last_input_stamp = max(self.last_input_stamp, msg.header.stamp.to_sec())

    def on_alarm(self, msg):
        if msg.header.stamp.to_sec() > self.ended_stamp:  # not a latched alarm of an event already written
            self.in_event = True
            self.quiet_since = None

    def on_states(self, msg):
        t = msg.header.stamp.to_sec()
        if t > self.last_states_stamp:
            self.last_states_stamp, self.last_progress_wall = t, time.time()
        moving = any(s.mode in (1, 2, 3) for s in msg.items)
        if moving and t > self.ended_stamp:  # an item still frozen mid-rock after the input stopped opens nothing
            self.in_event, self.quiet_since = True, None
        elif self.in_event:
            t = msg.header.stamp.to_sec()
            self.quiet_since = self.quiet_since if self.quiet_since is not None else t
            if t - self.quiet_since >= self.quiet_time:
                self.finish('every item at rest or overturned for %.1f s' % self.quiet_time)

    def watch(self):
        import rospy
        while not rospy.is_shutdown():
            time.sleep(0.2)
            with self.lock:
                last = max(self.last_input_wall or 0.0, self.last_progress_wall or 0.0)
                # Idle: no input and no newer states for idle_timeout, and the states this node has seen
                # have caught up with the input (a large catalogue's states arrive, and deserialize here,
                # well after their samples; 1 s covers the ~states period and the timer's phase).
                caught_up = self.last_states_stamp >= self.last_input_stamp - CAUGHT_UP
                if self.in_event and last > 0.0 and time.time() - last > self.idle_timeout and caught_up:
                    self.finish('no input for %.1f s' % self.idle_timeout)

    def finish(self, why):
        """Called with the lock held: hands the event's messages to a writer thread."""
        events, self.buffer = list(self.buffer), collections.deque()
        self.in_event, self.quiet_since = False, None
        self.ended_stamp = max(self.ended_stamp, self.last_states_stamp)
        if not any(t == self.monitor + '/states' for t, _, _ in events):
            import rospy
            rospy.logwarn('rocking_report: an event ended (%s) with no %s/states recorded: no report', why, self.monitor)
            return
        threading.Thread(target=self.write, args=(events, why)).start()

    def write(self, events, why):
        import rosbag
        import rospy
        from std_msgs.msg import String
        inputs = [m.header.stamp.to_sec() for t, m, _ in events if t in self.inputs and not m.header.stamp.is_zero()]
        stamp = min(inputs) if inputs else time.time()
        base = os.path.join(self.dir, 'event_' + time.strftime('%Y%m%dT%H%M%SZ', time.gmtime(stamp)))
        n = 1
        while os.path.exists(base + ('' if n == 1 else '_%d' % n) + '.bag'):
            n += 1
        base += '' if n == 1 else '_%d' % n
        try:
            with rosbag.Bag(base + '.bag', 'w') as bag:
                # The catalogue, for the items' Housner periods: from the parameter server, as the monitor read it.
                cat = {'items': rospy.get_param(self.monitor + '/items', [])}
                bag.write('/rocking_report/catalogue', String(data=json.dumps(cat)), events[0][2] if events else rospy.Time.now())
                for topic, msg, t in events:
                    bag.write(topic, msg, t)
            # The pair's other monitor raised nothing this event (or was down): the report is the monitor's.
            pair = self.pair if any(t == (self.pair or '') + '/alarms' for t, _, _ in events) else None
            if self.pair and not pair:
                rospy.loginfo('rocking_report: no alarm of the pair\'s other monitor %s in this event', self.pair)
            write_report(base + '.bag', base + '.html', monitor=self.monitor, pair=pair,
                         title='Post-event report, %s' % utc(stamp), ended=why,
                         journal=self.journal if self.journal and os.path.exists(self.journal) else None)
            self.reports += 1
            rospy.loginfo('rocking_report: event ended (%s): wrote %s.html and %s.bag', why, base, base)
        except (ReportError, OSError) as e:
            rospy.logerr('rocking_report: could not write the report of the event at %s: %s', utc(stamp), e)
