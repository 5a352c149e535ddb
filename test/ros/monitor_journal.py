#!/usr/bin/python3
"""rostest (test/ros/monitor_journal.test): no alarm lost or repeated across a kill -9.

The real Rinaldi record (Northridge 1994, 318 / 228 deg + UP) is streamed in real time to the monitor
(/journal_mon, ~journal in a scratch folder). Right after its first OVERTURNED alarm the monitor is
killed with SIGKILL; half of the journal's last line is appended (a power cut while writing). A new
monitor is started on the same journal, beside a control monitor without a journal (/journal_ctl),
and both are fed the rest of the record. Checked:
- the restarted monitor warns that the journal's last line is cut, naming file and line;
- every alarm of the first run is sent again to this (reconnected) subscriber exactly once, equal to
  the original (event id, sequence, times, plane);
- it alarms no (item, level) of the first run again, although the control, the same monitor on the
  same samples without the journal, does (so the check can fail);
- its new alarms are the control's others, at the same times, in the same event, numbered on;
- ~reset closes the event: a reset line in the journal, nothing sent to a new subscriber.
"""
import json
import os
import signal
import subprocess
import tempfile
import threading
import time
import unittest

import roslib.packages
import rosbag
import rospy
import rostest
from rocking_monitor.msg import OverturnAlarm, RockingStateArray
from sensor_msgs.msg import Imu
from std_srvs.srv import Trigger

OVERTURNED = 4


def wait_for(what, predicate, timeout=20.0):
    deadline = time.time() + timeout
    while time.time() < deadline:
        if predicate():
            return
        time.sleep(0.02)
    raise AssertionError('timed out waiting for ' + what)


class Monitor:
    """A monitor process and what this test received from it."""

    def __init__(self, name, log_path):
        self.name = name
        self.alarms = []
        self.acked = 0.0
        self.moving = []  # input stamp at which its first item left rest (empty until then)
        self.lock = threading.Lock()
        self.on_alarm = None
        self.log_path = log_path
        exe = [p for p in roslib.packages.find_node('rocking_monitor', 'monitor') if os.access(p, os.X_OK)][0]
        self.log = open(log_path, 'w')
        self.proc = subprocess.Popen([exe, '__name:=' + name], stdout=self.log, stderr=subprocess.STDOUT)
        self.sub_a = rospy.Subscriber('/%s/alarms' % name, OverturnAlarm, self._alarm, queue_size=1000)
        self.sub_s = rospy.Subscriber('/%s/states' % name, RockingStateArray, self._state, queue_size=1000)

    def _alarm(self, m):
        with self.lock:
            self.alarms.append(m)
        if self.on_alarm is not None:
            self.on_alarm(m)

    def _state(self, m):
        self.acked = m.header.stamp.to_sec()
        if not self.moving and any(i.mode > 0 for i in m.items):
            self.moving.append(self.acked)

    def text(self):
        self.log.flush()
        with open(self.log_path) as f:
            return f.read()

    def close(self):
        self.sub_a.unregister()
        self.sub_s.unregister()
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self.proc.kill()
        self.log.close()


def key(m):
    return (m.item_id, m.level)


def record_samples(test, record, scratch, extra=()):
    """The Imu samples of a record (record_to_bag into scratch; more component files in extra)."""
    bag_path = os.path.join(scratch, 'record.bag')
    args = [os.path.join(rospy.get_param('~tools'), 'record_to_bag'), '--file', record]
    for f in extra:
        args += ['--file', f]
    out = subprocess.run(args + ['-o', bag_path], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    test.assertEqual(out.returncode, 0, out.stdout)
    with rosbag.Bag(bag_path) as bag:
        return [m for _, m, _ in bag.read_messages(topics=['/ground/imu'])]


class Journal(unittest.TestCase):
    def test_kill_restart_alarms_once(self):
        records = rospy.get_param('~records')
        paths = [os.path.join(records, rospy.get_param(p)) for p in ('~horizontal', '~horizontal_y', '~vertical')]
        if not all(os.path.exists(p) for p in paths):
            print('NOTICE: records not found (%s): journal restart test skipped' % paths[0])
            self.skipTest('records not found')
        scratch = tempfile.mkdtemp(prefix='rocking_journal_')
        bag_path = os.path.join(scratch, 'rinaldi.bag')
        out = subprocess.run([os.path.join(rospy.get_param('~tools'), 'record_to_bag'), '--file', paths[0], '--file',
                              paths[1], '--file', paths[2], '-o', bag_path],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        self.assertEqual(out.returncode, 0, out.stdout)
        with rosbag.Bag(bag_path) as bag:
            samples = [m for _, m, _ in bag.read_messages(topics=['/ground/imu'])]
        self.assertEqual(len(samples), 1991)
        t0 = samples[0].header.stamp
        journal = os.path.join(scratch, 'journal', 'journal.jsonl')  # the folder does not exist yet
        rospy.set_param('/journal_mon/journal', journal)
        imu = rospy.Publisher('/ground/imu', Imu, queue_size=4000)

        def stream(monitors, begin, end, on_each=None):
            """Samples [begin, end) restamped on the wall clock in real time, in lock-step with the monitors'
            states (one per sample from the second on). Returns the index reached."""
            base = rospy.Time.now() + rospy.Duration(0.05)
            for i in range(begin, end):
                m = samples[i]
                m.header.stamp = base + (samples_t[i] - samples_t[begin])
                stamp = m.header.stamp.to_sec()
                while rospy.Time.now().to_sec() < stamp:
                    time.sleep(0.0005)
                imu.publish(m)
                if i > begin:
                    deadline = time.time() + 30.0  # lock-step: a loaded machine may take long (issue 42)
                    while any(mon.acked < stamp - 1e-6 for mon in monitors) and time.time() < deadline:
                        time.sleep(0.0002)
                if on_each is not None and on_each(i):
                    return i + 1
            return end

        samples_t = [m.header.stamp - t0 for m in samples]

        # 1. The first monitor, killed right after its first OVERTURNED alarm.
        first = Monitor('journal_mon', os.path.join(scratch, 'monitor1.log'))
        killed = threading.Event()

        def kill_on_overturn(m):
            if m.level == OVERTURNED and not killed.is_set():
                os.kill(first.proc.pid, signal.SIGKILL)  # from the subscriber's thread: nothing more is sent
                killed.set()

        first.on_alarm = kill_on_overturn
        wait_for('the first monitor', lambda: imu.get_num_connections() > 0 and first.sub_s.get_num_connections() > 0)
        stop = stream([first], 0, len(samples), on_each=lambda i: killed.is_set())
        self.assertTrue(killed.is_set(), 'no OVERTURNED alarm in the whole record: ' + first.text()[-2000:])
        first.proc.wait(timeout=30)
        self.assertEqual(first.proc.returncode, -signal.SIGKILL)
        time.sleep(0.3)
        before = list(first.alarms)
        first.close()
        overturned = [m for m in before if m.level == OVERTURNED][0]
        rospy.loginfo('killed after sample %d of %d: %s OVERTURNED, event %s #%d; %d alarms before the kill', stop,
                      len(samples), overturned.item_id, overturned.event_id, overturned.sequence, len(before))
        self.assertTrue(overturned.event_id)
        self.assertEqual(len({key(m) for m in before}), len(before), 'a level alarmed twice in one run')
        self.assertEqual(sorted(m.sequence for m in before), list(range(1, len(before) + 1)))

        # The journal holds exactly what was published, one whole line each; then the power goes off
        # in the middle of the next line.
        with open(journal) as f:
            lines = f.read().splitlines()
        records = [json.loads(l) for l in lines]
        self.assertEqual([(r['item'], r['sequence'], r['event']) for r in records],
                         [(m.item_id, m.sequence, m.event_id) for m in before])
        self.assertEqual(records[-1]['time'], overturned.event_time)
        with open(journal, 'a') as f:
            f.write(lines[-1][:len(lines[-1]) // 2])

        # 2. The restarted monitor on the same journal, beside the control without one.
        second = Monitor('journal_mon', os.path.join(scratch, 'monitor2.log'))
        control = Monitor('journal_ctl', os.path.join(scratch, 'control.log'))
        wait_for('both monitors', lambda: imu.get_num_connections() >= 2 and second.sub_s.get_num_connections() > 0
                 and control.sub_s.get_num_connections() > 0)
        wait_for('the alarms read back from the journal', lambda: len(second.alarms) >= len(before), timeout=30.0)
        time.sleep(0.5)
        resent = list(second.alarms)
        self.assertIn('%s:%d: last line cut in the middle' % (journal, len(lines) + 1), second.text())
        self.assertEqual(len(resent), len(before), 'each alarm of the first run is sent again exactly once')
        for a, b in zip(before, resent):
            self.assertEqual((b.item_id, b.level, b.plane, b.event_id, b.sequence, b.event_time, b.header.stamp),
                             (a.item_id, a.level, a.plane, a.event_id, a.sequence, a.event_time, a.header.stamp))
        stream([second, control], stop, len(samples))
        time.sleep(1.0)
        after = list(second.alarms)[len(resent):]
        ctl = list(control.alarms)
        rospy.loginfo('after the restart: control %d alarms, restarted monitor %d new ones', len(ctl), len(after))
        # ~reset closes the event: journaled, and a new subscriber is sent nothing of it.
        rospy.wait_for_service('/journal_mon/reset', timeout=30)
        self.assertTrue(rospy.ServiceProxy('/journal_mon/reset', Trigger)().success)
        late = []
        late_sub = rospy.Subscriber('/journal_mon/alarms', OverturnAlarm, late.append, queue_size=100)
        wait_for('a new subscriber', lambda: late_sub.get_num_connections() > 0, timeout=30.0)
        time.sleep(1.0)
        late_sub.unregister()
        self.assertEqual(late, [], 'alarms of an event closed by ~reset sent to a new subscriber')
        second.close()
        control.close()

        old = {key(m) for m in before}
        repeated_by_control = [m for m in ctl if key(m) in old]
        self.assertIn(key(overturned), {key(m) for m in repeated_by_control},
                      'the control overturns the same item again after the restart: the check can fail')
        self.assertEqual([key(m) for m in after if key(m) in old], [], 'a level of the first run alarmed again')
        expected = [m for m in ctl if key(m) not in old]
        self.assertEqual([(key(m), m.plane, m.event_time) for m in after],
                         [(key(m), m.plane, m.event_time) for m in expected])
        for m in after:
            self.assertEqual(m.event_id, overturned.event_id)
        self.assertEqual([m.sequence for m in after], list(range(len(before) + 1, len(before) + 1 + len(after))))
        # The journal: the cut line is gone, every line whole, each (item, level) once in the event.
        with open(journal) as f:
            text = f.read()
        self.assertTrue(text.endswith('\n'))
        final = [json.loads(l) for l in text.splitlines()]
        self.assertEqual(final[-1]['kind'], 'reset')
        final = final[:-1]
        # Stale periods (the replay stopped while the node ran on) are journaled too: opened without
        # an end, closed with one after the start.
        stale = [r for r in final if r['kind'] == 'stale']
        for r in stale:
            self.assertTrue(r['sensor'])
            if 'end_time' in r:
                self.assertGreaterEqual(r['end_time'], r['time'])
        final = [r for r in final if r['kind'] != 'stale']
        self.assertEqual(len(final), len(before) + len(after))
        self.assertEqual(len({(r['item'], r['level']) for r in final}), len(final))


if __name__ == '__main__':
    rospy.init_node('monitor_journal_test')
    rostest.rosrun('rocking_monitor', 'monitor_journal', Journal)
