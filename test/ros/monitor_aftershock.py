#!/usr/bin/python3
"""rostest (test/ros/monitor_aftershock.test): an aftershock is a new event (issue 29 part 4).

The real Rinaldi 228 record, then 60 s of quiet input, then the same record again, streamed to the
example catalogue's monitor in lock-step (faster than real time; stamps in the past of the node's
clock). Between the two, the items on their side are set upright (~set_upright). Checked:
- the first event ends once the shaking has stopped: an 'end' record in the journal, numbered on;
- the second shaking is a new event (another id, sequence from 1) in which every (item, level) of the
  first alarms again, at the same time after the record's start (the same motion on the same items at
  rest), although it lies well within ~journal_window (3600 s) of the first;
- no (item, level) is alarmed twice within one event.
"""
import copy
import json
import os
import tempfile
import time
import unittest

import rospy
import rostest
from sensor_msgs.msg import Imu
from std_srvs.srv import Trigger

from monitor_journal import Monitor, key, record_samples, wait_for


class Aftershock(unittest.TestCase):
    def test_second_shaking_is_a_new_event(self):
        path = os.path.join(rospy.get_param('~records'), rospy.get_param('~record'))
        if not os.path.exists(path):
            print('NOTICE: record not found (%s): aftershock test skipped' % path)
            self.skipTest('record not found')
        scratch = tempfile.mkdtemp(prefix='rocking_aftershock_')
        samples = record_samples(self, path, scratch)
        offsets = [m.header.stamp - samples[0].header.stamp for m in samples]
        dt = offsets[1]
        journal = os.path.join(scratch, 'journal.jsonl')
        rospy.set_param('/aftershock_mon/journal', journal)
        imu = rospy.Publisher('/ground/imu', Imu, queue_size=4000)
        mon = Monitor('aftershock_mon', os.path.join(scratch, 'monitor.log'))
        self.addCleanup(mon.close)  # also when an assertion fails
        wait_for('the monitor', lambda: imu.get_num_connections() > 0 and mon.sub_s.get_num_connections() > 0)
        time.sleep(0.5)
        quiet = copy.deepcopy(samples[0])
        quiet.linear_acceleration.x = quiet.linear_acceleration.y = 0.0
        quiet.linear_acceleration.z = 9.80665  # at rest: gravity only (the fixed baseline)
        # Stamps in the past of the node's clock (never ahead of it), one every dt.
        t = rospy.Time.now() - rospy.Duration(200.0)

        def send(m, stamp):
            m.header.stamp = stamp
            imu.publish(m)
            deadline = time.time() + 30.0  # lock-step: a loaded machine may take long (issue 42)
            while mon.acked < stamp.to_sec() - 1e-6 and time.time() < deadline:
                time.sleep(0.0002)

        starts = []
        for play in range(2):
            starts.append(t.to_sec())
            for i, m in enumerate(samples):
                send(m, t + offsets[i])
            t = t + offsets[-1] + dt
            for _ in range(int(round(60.0 / dt.to_sec()))):  # 60 s of quiet input
                send(quiet, t)
                t = t + dt
            if play == 0:
                wait_for('the end of the first event', lambda: 'ended: shaking stopped' in mon.text(), timeout=30.0)
                rospy.wait_for_service('/aftershock_mon/set_upright', timeout=30)
                self.assertTrue(rospy.ServiceProxy('/aftershock_mon/set_upright', Trigger)().success)
        time.sleep(1.0)
        alarms = list(mon.alarms)
        mon.close()

        events = []
        for m in alarms:
            if not events or events[-1][0] != m.event_id:
                events.append((m.event_id, []))
            events[-1][1].append(m)
        self.assertEqual(len(events), 2, 'expected two events: %s' % [e[0] for e in events])
        (id1, first), (id2, second) = events
        self.assertNotEqual(id1, id2)
        for ev in (first, second):
            self.assertEqual(len({key(m) for m in ev}), len(ev), 'a level alarmed twice in one event')
            self.assertEqual(sorted(m.sequence for m in ev)[0], 1)
        rel = lambda ev, start: sorted((key(m), round(m.event_time - start, 6)) for m in ev)
        self.assertGreaterEqual(len(first), 5)
        self.assertEqual(rel(second, starts[1]), rel(first, starts[0]))
        with open(journal) as f:
            records = [json.loads(l) for l in f.read().splitlines()]
        ends = [r for r in records if r['kind'] == 'end']
        self.assertEqual(len(ends), 2, [r['kind'] for r in records])
        self.assertEqual(ends[0]['event'], id1)
        self.assertIn('shaking stopped', ends[0]['reason'])
        self.assertEqual(ends[0]['sequence'], max(r['sequence'] for r in records if r.get('event') == id1))
        rospy.loginfo('first event %s: %d alarms; second event %s: %d alarms, the same (item, level, time after '
                      'the record start)', id1, len(first), id2, len(second))


if __name__ == '__main__':
    rospy.init_node('monitor_aftershock_test')
    rostest.rosrun('rocking_monitor', 'monitor_aftershock', Aftershock)
