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
import unittest

import roslib.packages
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
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
        self.diag = None
        self.subs = [rospy.Subscriber('/conflict/imu', Imu, self.on_imu, queue_size=1000),
                     rospy.Subscriber('/diagnostics', DiagnosticArray, self.on_diag, queue_size=100)]

    def on_imu(self, msg):
        with self.cond:
            self.imu.append((msg.header.seq, msg.linear_acceleration.x, tuple(msg.linear_acceleration_covariance)))
            self.cond.notify_all()

    def on_diag(self, msg):
        with self.cond:
            for st in msg.status:
                if st.name.startswith('conflict:'):
                    self.diag = (st.level, st.message, {kv.key: kv.value for kv in st.values})
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


if __name__ == '__main__':
    rospy.init_node('udp_conflicts_test')
    rostest.rosrun('rocking_monitor', 'udp_conflicts', ConflictsTest)
