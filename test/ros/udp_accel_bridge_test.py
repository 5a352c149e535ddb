#!/usr/bin/python3
"""rostest: a real record sent to udp_accel_bridge as datagrams (binary and text), with 1 % seeded
drops and seeded adjacent swaps. Every published sample must be the record's sample at its place,
in order; /diagnostics must count exactly the drops, swaps and the one malformed datagram sent. Each bridge's
~history (issue 29 part 2) must serve exactly the samples it published after a given stamp, and say when
its ring (table_bin: 5 s) no longer reaches back that far."""
import os
import random
import socket
import struct
import subprocess
import time
import unittest

import roslib.packages

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from sensor_msgs.msg import Imu
from rocking_monitor.srv import SampleHistory

G = 9.80665
DT = 0.01
T0 = 1000.0  # the controller's clock at the first sample, s


def read_at2(path):
    """PEER AT2 values in m/s^2 (4 header lines, then the values; units of g)."""
    with open(path) as f:
        lines = f.read().splitlines()
    values = [float(tok) * G for line in lines[4:] for tok in line.split()]
    npts = int(lines[3].split('NPTS=')[1].split(',')[0])
    return values[:npts]


def plan(n, seed):
    """Send order with 1 % drops and 2 % adjacent swaps (never the first or last sample)."""
    rng = random.Random(seed)
    order = list(range(n))
    dropped, swaps = set(), 0
    i = 1
    while i + 2 < n:
        if rng.random() < 0.02:
            order[i], order[i + 1] = order[i + 1], order[i]
            swaps += 1
            i += 2
            continue
        if rng.random() < 0.01:
            dropped.add(order[i])
        i += 1
    return [k for k in order if k not in dropped], dropped, swaps


class UdpAccelBridgeTest(unittest.TestCase):
    def load_record(self):
        d = os.path.join(rospy.get_param('~records_dir'), 'northridge_1994')
        if not os.path.isfile(os.path.join(d, 'Rinaldi228.AT2')):
            self.skipTest('records directory not found: ' + d)
        self.x = read_at2(os.path.join(d, 'Rinaldi228.AT2'))
        self.y = read_at2(os.path.join(d, 'Rinaldi318.AT2'))
        self.z = read_at2(os.path.join(d, 'RinaldiUP.AT2'))
        self.n = min(len(self.x), len(self.y), len(self.z))
        self.got = {'bin': [], 'txt': []}
        self.diag = {}
        self.subs = [rospy.Subscriber('/table_%s/imu' % k, Imu, self.on_imu, callback_args=k, queue_size=100000)
                     for k in ('bin', 'txt')]
        self.diag_sub = rospy.Subscriber('/diagnostics', DiagnosticArray, self.on_diag, queue_size=100)

    def on_imu(self, msg, key):
        self.got[key].append(msg)

    def on_diag(self, msg):
        for st in msg.status:
            for key in ('bin', 'txt'):
                if st.name.startswith('table_%s:' % key):
                    self.diag[key] = {kv.key: kv.value for kv in st.values}

    def test_record_through_the_bridge(self):
        self.load_record()
        deadline = time.time() + 20
        while any(s.get_num_connections() == 0 for s in self.subs):
            self.assertLess(time.time(), deadline, 'bridges not publishing')
            time.sleep(0.1)
        time.sleep(0.5)
        order, dropped, swaps = plan(self.n, 18)
        self.assertGreater(len(dropped), 5)
        self.assertGreater(swaps, 10)
        sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        for count, i in enumerate(order):
            t = T0 + i * DT
            sock.sendto(struct.pack('<4sHHQdddd', b'RMAC', 1, 0, 5000 + i, t, self.x[i], self.y[i], self.z[i]),
                        ('127.0.0.1', PORT_BIN))
            sock.sendto(('%r,%r,%r,%r\n' % (t, self.x[i], self.y[i], self.z[i])).encode(), ('127.0.0.1', PORT_TXT))
            if count == 100:  # one malformed datagram each: counted, not published
                sock.sendto(b'RMAC' + bytes(40), ('127.0.0.1', PORT_BIN))
                sock.sendto(b'12.0,1,2\n', ('127.0.0.1', PORT_TXT))
            time.sleep(0.0005)  # well below loopback capacity: the only losses are the injected ones
        want = sorted(order)
        deadline = time.time() + 20
        while time.time() < deadline and not all(
                k in self.diag and int(self.diag[k]['published']) == len(want) and len(self.got[k]) == len(want)
                for k in ('bin', 'txt')):
            time.sleep(0.2)
        time.sleep(1.0)  # one more diagnostics period
        for key in ('bin', 'txt'):
            msgs = self.got[key]
            self.assertEqual(len(msgs), len(want), key)
            first = msgs[0].header.stamp.to_sec()
            places = [int(round((m.header.stamp.to_sec() - first) / DT)) for m in msgs]
            self.assertEqual(places, want, key + ': published in order, exactly the samples sent')
            for m, i in zip(msgs, places):
                self.assertEqual(m.linear_acceleration.x, self.x[i], '%s sample %d' % (key, i))
                self.assertEqual(m.linear_acceleration.y, self.y[i], '%s sample %d' % (key, i))
                self.assertEqual(m.linear_acceleration.z, self.z[i] + G, '%s sample %d' % (key, i))
                self.assertEqual(m.orientation_covariance[0], -1.0)
                self.assertEqual(m.angular_velocity_covariance[0], -1.0)
            d = self.diag[key]
            self.assertEqual(int(d['lost']), len(dropped), key)
            self.assertEqual(int(d['reordered (published in order)']), swaps, key)
            self.assertEqual(int(d['late (dropped)']), 0, key)
            self.assertEqual(int(d['duplicates (dropped)']), 0, key)
            self.assertEqual(int(d['malformed']), 1, key)
            self.assertEqual(int(d['datagrams']), len(order) + 1, key)
            self.assertEqual(d['form'], 'binary' if key == 'bin' else 'text')
            # issue 54: the buffer the kernel granted, read back (Linux: twice min(asked, rmem_max))
            with open('/proc/sys/net/core/rmem_max') as f:
                granted = 2 * min(4 << 20, int(f.read()))
            self.assertEqual(int(d['receive buffer (bytes)']), granted, key)
        rospy.loginfo('udp_accel_bridge: %d samples, %d dropped, %d swapped: all counted', self.n, len(dropped), swaps)
        self.check_history()

    def check_history(self):
        """~history against the messages this test received from each bridge."""
        def served(key, after, topic=None):
            rospy.wait_for_service('/table_%s/history' % key, timeout=30)
            call = rospy.ServiceProxy('/table_%s/history' % key, SampleHistory)
            return call(topic or '/table_%s/imu' % key, after)

        def same(key, res, msgs):
            self.assertEqual(len(res.stamps), len(msgs), key)
            for s, x, y, z, m in zip(res.stamps, res.x, res.y, res.z, msgs):
                self.assertEqual((s, x, y, z), (m.header.stamp, m.linear_acceleration.x, m.linear_acceleration.y,
                                                m.linear_acceleration.z), key)

        # The text bridge keeps the default minutes: everything after its first sample, complete.
        msgs = self.got['txt']
        res = served('txt', msgs[0].header.stamp)
        self.assertTrue(res.ok and res.complete, res.message)
        self.assertEqual((res.type, res.frame_id), ('sensor_msgs/Imu', 'accelerometer'))
        same('txt', res, msgs[1:])
        # From before it started: all it has, but not complete (it never had what came before).
        res = served('txt', rospy.Time(0))
        self.assertTrue(res.ok and not res.complete, res.message)
        same('txt', res, msgs)
        res = served('txt', msgs[700].header.stamp)
        self.assertTrue(res.complete, res.message)
        same('txt', res, msgs[701:])
        # Another topic: refused, naming what it keeps.
        res = served('txt', rospy.Time(0), '/elsewhere/imu')
        self.assertFalse(res.ok)
        self.assertIn('/table_txt/imu', res.message)
        # The binary bridge keeps 5 s (501 samples): within them complete, before them not.
        msgs = self.got['bin']
        res = served('bin', msgs[-301].header.stamp)
        self.assertTrue(res.ok and res.complete, res.message)
        same('bin', res, msgs[-300:])
        res = served('bin', msgs[-502].header.stamp)  # the newest sample overwritten: nothing after it lost
        self.assertTrue(res.complete, res.message)
        same('bin', res, msgs[-501:])
        res = served('bin', msgs[-503].header.stamp)  # one sample after it was overwritten
        self.assertFalse(res.complete, res.message)
        self.assertEqual(res.oldest, msgs[-501].header.stamp)
        same('bin', res, msgs[-501:])

    # A bad parameter or a port in use: one FATAL line naming it, exit status 2.
    def run_bridge(self, *args):
        exe = [p for p in roslib.packages.find_node('rocking_monitor', 'udp_accel_bridge') if os.access(p, os.X_OK)][0]
        r = subprocess.run([exe, '__name:=bad_bridge_%d' % random.randrange(1 << 30)] + list(args),
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=30)
        return r.returncode, r.stdout.decode(errors='replace')

    def test_bad_parameters(self):
        code, out = self.run_bridge('_port:=15699')
        self.assertEqual(code, 2, out)
        self.assertIn("~rate_hz must be the controller's sample rate, > 0 Hz", out)
        code, out = self.run_bridge('_rate_hz:=100.0', '_clock:=gps', '_port:=15699')
        self.assertEqual(code, 2, out)
        self.assertIn("~clock must be first_arrival or controller, not 'gps'", out)
        code, out = self.run_bridge('_rate_hz:=100.0', '_port:=%d' % PORT_BIN, '_bind_address:=127.0.0.1')  # the test's bridge has it
        self.assertEqual(code, 2, out)
        self.assertIn('cannot bind 127.0.0.1:%d' % PORT_BIN, out)
        code, out = self.run_bridge('_rate_hz:=100.0', '_port:=15699', '_history_length:=-5')
        self.assertEqual(code, 2, out)
        self.assertIn('~history_length: -5.000000 s must be in [0, 86400] (0 = no history)', out)
        code, out = self.run_bridge('_rate_hz:=100.0', '_port:=15699', '_history_length:=long')
        self.assertEqual(code, 2, out)
        self.assertIn('~history_length: must be a number of seconds (0 = no history)', out)


if __name__ == '__main__':
    rospy.init_node('udp_accel_bridge_test')
    # The bridges' ports, from the launch file: each build directory has its own (test_environment.cmake).
    PORT_BIN = int(rospy.get_param('~port_bin'))
    PORT_TXT = int(rospy.get_param('~port_txt'))
    rostest.rosrun('rocking_monitor', 'udp_accel_bridge', UdpAccelBridgeTest)
