#!/usr/bin/python3
"""rostest (issue 52): udp_accel_bridge with ~allowed_senders publishes only the pinned sender's
datagrams; an intruder on loopback from another port and one from 127.0.0.2 are dropped and counted per
source in /diagnostics. A bridge with no list warns, and reports ERROR naming both once a second
source feeds it. Bad entries stop the node with a FATAL line naming the parameter and the entry."""
import os
import random
import struct
import socket
import subprocess
import threading
import unittest

import roslib.packages
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from sensor_msgs.msg import Imu

WAIT_S = 30.0  # a condition wait's bound on a loaded machine, never a verdict by itself


def datagram(seq, t, ax):
    return struct.pack('<4sHHQdddd', b'RMAC', 1, 0, seq, t, ax, 0.0, 0.0)


def sender(address, port):
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    s.bind((address, port))
    return s


class AllowedSendersTest(unittest.TestCase):
    def setUp(self):
        self.cond = threading.Condition()
        self.imu = {'pinned': [], 'open': []}
        self.diag = {}
        self.subs = [rospy.Subscriber('/%s/imu' % k, Imu, self.on_imu, callback_args=k, queue_size=10000)
                     for k in ('pinned', 'open')]
        self.subs.append(rospy.Subscriber('/diagnostics', DiagnosticArray, self.on_diag, queue_size=100))

    def on_imu(self, msg, key):
        with self.cond:
            self.imu[key].append(msg.linear_acceleration.x)
            self.cond.notify_all()

    def on_diag(self, msg):
        with self.cond:
            for st in msg.status:
                for key in ('pinned', 'open'):
                    if st.name.startswith(key + ':'):
                        self.diag[key] = (st.level, st.message, {kv.key: kv.value for kv in st.values})
            self.cond.notify_all()

    def wait_for(self, what, predicate):
        with self.cond:
            ok = self.cond.wait_for(predicate, timeout=WAIT_S)
        self.assertTrue(ok, 'waited %.0f s for %s; diagnostics: %s' % (WAIT_S, what, self.diag))

    def test_only_the_pinned_sender_is_published(self):
        good = sender('127.0.0.1', BASE + 6)
        other_port = sender('127.0.0.1', BASE + 7)
        other_host = sender('127.0.0.2', BASE + 6)  # same port, another address
        dest = ('127.0.0.1', BASE + 5)
        # Interleaved: the intruders send the same sequence numbers with other values first.
        for seq in range(20):
            other_port.sendto(datagram(seq, seq * 0.01, -1.0), dest)
            other_host.sendto(datagram(seq, seq * 0.01, -2.0), dest)
            if seq < 7:
                other_host.sendto(datagram(seq + 100, seq * 0.01, -2.0), dest)
            good.sendto(datagram(seq, seq * 0.01, float(seq)), dest)
        # 20 samples sent; the window holds none back after idle_flush, so all 20 arrive.
        self.wait_for('20 published samples', lambda: len(self.imu['pinned']) >= 20)
        dropped = lambda: self.diag.get('pinned', (0, '', {}))[2].get('dropped (sender not allowed)')
        self.wait_for('47 dropped datagrams in /diagnostics', lambda: dropped() == '47')
        with self.cond:
            self.assertEqual(self.imu['pinned'], [float(k) for k in range(20)])
            level, message, values = self.diag['pinned']
        self.assertEqual(level, DiagnosticStatus.WARN)
        self.assertEqual(values['senders dropped'],
                         '127.0.0.1:%d (20), 127.0.0.2:%d (27)' % (BASE + 7, BASE + 6))
        self.assertEqual(values['senders admitted'], '127.0.0.1:%d (20)' % (BASE + 6))
        self.assertIn('127.0.0.2:%d (27)' % (BASE + 6), message)
        self.assertEqual(values['samples accepted'], '20')
        for s in (good, other_port, other_host):
            s.close()

    def test_no_list_warns_then_errs_on_a_second_source(self):
        dest = ('127.0.0.1', BASE + 8)
        first = sender('127.0.0.1', 0)
        first.sendto(datagram(0, 0.0, 1.0), dest)
        self.wait_for('the first sample', lambda: len(self.imu['open']) >= 1)
        msg = lambda: self.diag.get('open', (0, '', {}))[1]
        self.wait_for('the no-list warning',
                      lambda: 'no allowed_senders: any host on the network can feed ground motion' in msg())
        self.assertEqual(self.diag['open'][0], DiagnosticStatus.WARN)
        second = sender('127.0.0.2', 0)
        second.sendto(datagram(1, 0.01, 2.0), dest)
        a = '127.0.0.1:%d' % first.getsockname()[1]
        b = '127.0.0.2:%d' % second.getsockname()[1]
        self.wait_for('ERROR naming both senders', lambda: self.diag['open'][0] == DiagnosticStatus.ERROR)
        self.assertIn('several senders feed one stream', msg())
        self.assertIn(a + ' (1)', msg())
        self.assertIn(b + ' (1)', msg())
        # Issue 52 part 2: sequence 1 again with another value is a conflict: the first is kept.
        first.sendto(datagram(1, 0.01, 5.0), dest)
        conflicts = lambda: self.diag['open'][2].get('conflicts (same sequence, other values: dropped, first kept)')
        self.wait_for('one conflict in /diagnostics', lambda: conflicts() == '1')
        self.assertEqual(self.diag['open'][0], DiagnosticStatus.ERROR)
        self.assertIn('1 sequence numbers sent twice with different values (first kept)', msg())
        self.wait_for('two published samples', lambda: len(self.imu['open']) >= 2)
        with self.cond:
            self.assertEqual(self.imu['open'], [1.0, 2.0])
        first.close()
        second.close()

    def run_bridge(self, *args):
        exe = [p for p in roslib.packages.find_node('rocking_monitor', 'udp_accel_bridge') if os.access(p, os.X_OK)][0]
        r = subprocess.run([exe, '__name:=bad_senders_%d' % random.randrange(1 << 30), '_rate_hz:=100.0',
                            '_port:=%d' % (BASE + 9)] + list(args),
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=30)
        return r.returncode, r.stdout.decode(errors='replace')

    def test_bad_entries_stop_the_node(self):
        code, out = self.run_bridge('_allowed_senders:=10.0.0.1,10.0.0.5/24')
        self.assertEqual(code, 2, out)
        self.assertIn("~allowed_senders entry '10.0.0.5/24': host bits are set beyond /24", out)
        code, out = self.run_bridge('_allowed_senders:=controller.lab')
        self.assertEqual(code, 2, out)
        self.assertIn("~allowed_senders entry 'controller.lab': not an IPv4 address", out)


if __name__ == '__main__':
    rospy.init_node('udp_allowed_senders_test')
    BASE = int(rospy.get_param('~base'))
    rostest.rosrun('rocking_monitor', 'udp_allowed_senders', AllowedSendersTest)
