#!/usr/bin/python3
"""rostest (issue 52 item 3): udp_accel_bridge keeps the first of two datagrams with one sequence
number and different values, counts the conflict, turns /diagnostics ERROR, and marks the kept sample
on the published Imu when it was still held (linear_acceleration_covariance diagonal = +inf; the
values are the first datagram's). A conflict found after its sample was published is counted and
named by sequence number, not marked."""
import math
import os
import socket
import struct
import subprocess
import threading
import time
import unittest

import roslib.packages
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from rocking_monitor.msg import RockingStateArray
from sensor_msgs.msg import Imu

WAIT_S = 30.0  # a condition wait's bound on a loaded machine, never a verdict by itself


def v1(seq, ax):
    return struct.pack('<4sHHQdddd', b'RMAC', 1, 0, seq, seq * 0.01, ax, 0.0, 0.0)


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(('127.0.0.1', 0))
        return s.getsockname()[1]


class ConflictsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        exe = [p for p in roslib.packages.find_node('rocking_monitor', 'udp_accel_bridge') if os.access(p, os.X_OK)][0]
        cls.port = free_port()
        # idle_flush long: the held sample must wait for its missing predecessor, not for the clock.
        cls.proc = subprocess.Popen([exe, '__name:=conflict', '_rate_hz:=100.0', '_port:=%d' % cls.port,
                                     '_topic:=/conflict/imu', '_history_length:=0', '_reorder_window:=4',
                                     '_idle_flush:=30.0', '_linear_acceleration_variance:=0.25'])

    @classmethod
    def tearDownClass(cls):
        cls.proc.terminate()
        cls.proc.wait(timeout=30)

    def setUp(self):
        self.cond = threading.Condition()
        self.imu = []
        self.published = []  # (stamp ns, marked) of every Imu, in order
        self.diag = None
        self.monitor = None  # the monitor's status of its sensor
        self.stepped = set()  # input stamps the monitor stepped its box at (~states)
        self.subs = [rospy.Subscriber('/conflict/imu', Imu, self.on_imu, queue_size=1000),
                     rospy.Subscriber('/diagnostics', DiagnosticArray, self.on_diag, queue_size=100),
                     rospy.Subscriber('/rocking_monitor/states', RockingStateArray, self.on_states, queue_size=1000)]

    def on_imu(self, msg):
        with self.cond:
            self.imu.append((msg.header.seq, msg.linear_acceleration.x, tuple(msg.linear_acceleration_covariance)))
            # (stamp ns, marked): the stamps as ints (rospy.Time hashes by identity); header.seq is
            # the publisher's own count, not the datagram's sequence number
            self.published.append((msg.header.stamp.to_nsec(), math.isinf(msg.linear_acceleration_covariance[0])))
            self.cond.notify_all()

    def on_diag(self, msg):
        with self.cond:
            for st in msg.status:
                if st.name.startswith('conflict:'):
                    self.diag = (st.level, st.message, {kv.key: kv.value for kv in st.values})
                if st.name == 'rocking_monitor: sensor table samples':
                    self.monitor = (st.level, st.message, {kv.key: kv.value for kv in st.values})
            self.cond.notify_all()

    def on_states(self, msg):
        with self.cond:
            self.stepped.update(s.input_stamp.to_nsec() for s in msg.items if not s.input_stamp.is_zero())
            self.cond.notify_all()

    def wait_for(self, what, predicate):
        with self.cond:
            ok = self.cond.wait_for(predicate, timeout=WAIT_S)
        self.assertTrue(ok, 'waited %.0f s for %s; diagnostics: %s' % (WAIT_S, what, self.diag))

    def test_conflicts_keep_the_first_and_mark_it(self):
        self.wait_for('the bridge', lambda: self.diag is not None)
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        dest = ('127.0.0.1', self.port)
        s.sendto(v1(0, 0.5), dest)  # published at once
        self.wait_for('sample 0', lambda: len(self.imu) >= 1)
        s.sendto(v1(2, 2.5), dest)   # held: 1 is missing
        s.sendto(v1(2, -7.0), dest)  # conflict with the held sample: it is marked
        s.sendto(v1(0, 9.0), dest)   # conflict with a published sample: counted only
        s.sendto(v1(2, 2.5), dest)   # the same bytes again: a duplicate, not a conflict
        s.sendto(v1(1, 1.5), dest)   # releases 1 and 2
        self.wait_for('samples 1 and 2', lambda: len(self.imu) >= 3)
        count = lambda: self.diag[2].get('conflicts (same sequence, other values: dropped, first kept)')
        self.wait_for('2 conflicts in /diagnostics', lambda: count() == '2')
        with self.cond:
            imu = list(self.imu)
            level, message, values = self.diag
        self.assertEqual([(seq, x) for seq, x, _ in imu], [(0, 0.5), (1, 1.5), (2, 2.5)])
        plain = (0.25, 0.0, 0.0, 0.0, 0.25, 0.0, 0.0, 0.0, 0.25)
        self.assertEqual(imu[0][2], plain)
        self.assertEqual(imu[1][2], plain)
        marked = imu[2][2]
        self.assertTrue(all(math.isinf(marked[i]) and marked[i] > 0 for i in (0, 4, 8)), marked)
        self.assertEqual([marked[i] for i in (1, 2, 3, 5, 6, 7)], [0.0] * 6)
        self.assertEqual(level, DiagnosticStatus.ERROR)
        self.assertIn('2 sequence numbers sent twice with different values (first kept)', message)
        self.assertEqual(values['conflicts marked on the published sample (variance inf)'], '1')
        self.assertEqual(values['last conflict (sequence)'], '0')
        self.assertEqual(values['duplicates (dropped)'], '1')
        self.assertEqual(values['published'], '3')
        s.close()

    def test_monitor_does_not_step_on_the_marked_sample(self):
        """The monitor on the bridge's stream (its side of item 3): the marked sample is counted, not
        stepped, and its status is ERROR; the samples around it are stepped."""
        self.wait_for('the monitor', lambda: self.monitor is not None)
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        dest = ('127.0.0.1', self.port)
        received = lambda: int(self.monitor[2].get('received', '0'))
        seq = 100  # after the other test's numbers, or the first ever: the bridge takes either
        give_up = time.time() + WAIT_S  # a hang, not a verdict
        while True:  # in-order samples until the monitor has one: it is connected (a condition, not a delay)
            s.sendto(v1(seq, 0.0), dest)
            seq += 1
            with self.cond:
                if self.cond.wait_for(lambda: received() >= 1, timeout=2.0):
                    break
            self.assertLess(time.time(), give_up, 'the monitor never received a sample: %s' % (self.monitor,))
        s.sendto(v1(seq, 0.0), dest)       # stepped
        s.sendto(v1(seq + 2, 3.0), dest)   # held: seq + 1 is missing
        s.sendto(v1(seq + 2, -3.0), dest)  # a conflict with the held sample: published marked
        s.sendto(v1(seq + 1, 0.0), dest)   # releases seq + 1 and the marked seq + 2
        s.sendto(v1(seq + 3, 0.0), dest)   # the sample after it
        # the marked sample and the one after it published, the one after it stepped, and the monitor's
        # diagnostics naming the marked one (the monitor also saw the other test's conflict)
        marked = lambda: [t for t, m in self.published if m]
        after = lambda: [t for t, m in self.published if marked() and t > marked()[0]]
        named = lambda: abs(float(self.monitor[2]['last conflicting sample (stamp)']) - marked()[0] * 1e-9) < 1e-5
        self.wait_for('the monitor to step the sample after the marked one and name the marked one',
                      lambda: len(marked()) == 1 and after() and after()[0] in self.stepped and named())
        with self.cond:
            level, message, values = self.monitor
            stepped, published = set(self.stepped), sorted(self.published)
        k = [i for i, (_, m) in enumerate(published) if m][0]
        self.assertNotIn(published[k][0], stepped, 'the monitor stepped on the marked sample')
        self.assertIn(published[k - 1][0], stepped, 'the sample before it was not stepped')
        self.assertIn(published[k + 1][0], stepped)
        self.assertEqual(level, DiagnosticStatus.ERROR, message)
        self.assertIn('samples marked conflicting by the bridge', message)
        self.assertGreaterEqual(int(values['conflicting samples (marked by the bridge), not stepped']), 1)
        s.close()


if __name__ == '__main__':
    rospy.init_node('udp_conflicts_test')
    rostest.rosrun('rocking_monitor', 'udp_conflicts', ConflictsTest)
