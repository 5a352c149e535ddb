#!/usr/bin/python3
"""rostest (issue 52 item 2): udp_accel_bridge with ~key_file publishes only version-2 datagrams whose
HMAC-SHA256 tag, computed here with Python's standard hmac module, is right. A sender without the key
(version 1, text), one with a wrong key, a bit flipped in transit, and a replay of captured valid
datagrams: 0 published, each counted by kind and by source in /diagnostics. A bridge without a key
refuses version 2 (it cannot verify it). A key file that is missing, empty or readable by others stops
the node with a FATAL line naming the file and the reason."""
import hashlib
import hmac
import os
import random
import shutil
import socket
import struct
import subprocess
import tempfile
import threading
import unittest

import roslib.packages
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from sensor_msgs.msg import Imu

WAIT_S = 30.0  # a condition wait's bound on a loaded machine, never a verdict by itself
KEY = bytes(range(7, 39))  # 32 bytes, with a 0x0a (10) inside: raw bytes, not text
WRONG_KEY = bytes(range(8, 40))


def v1(seq, t, ax):
    return struct.pack('<4sHHQdddd', b'RMAC', 1, 0, seq, t, ax, 0.0, 0.0)


def v2(key, seq, t, ax):
    body = struct.pack('<4sHHQdddd', b'RMAC', 2, 0, seq, t, ax, 0.0, 0.0)
    return body + hmac.new(key, body, hashlib.sha256).digest()


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(('127.0.0.1', 0))
        return s.getsockname()[1]


def sender():
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(('127.0.0.1', 0))
    return s


def bridge_exe():
    return [p for p in roslib.packages.find_node('rocking_monitor', 'udp_accel_bridge') if os.access(p, os.X_OK)][0]


def bridge_args(name, port, *extra):
    return [bridge_exe(), '__name:=' + name, '_rate_hz:=100.0', '_port:=%d' % port, '_topic:=/%s/imu' % name,
            '_history_length:=0', '_bind_address:=127.0.0.1'] + list(extra)


class AuthenticatedTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix='rocking_key_')
        cls.key_file = os.path.join(cls.dir, 'table.key')
        with open(os.open(cls.key_file, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600), 'wb') as f:
            f.write(KEY)
        cls.ports = {'auth': free_port(), 'nokey': free_port()}
        cls.procs = [subprocess.Popen(bridge_args('auth', cls.ports['auth'], '_key_file:=' + cls.key_file)),
                     subprocess.Popen(bridge_args('nokey', cls.ports['nokey']))]

    @classmethod
    def tearDownClass(cls):
        for p in cls.procs:
            p.terminate()
            p.wait(timeout=30)
        shutil.rmtree(cls.dir)

    def setUp(self):
        self.cond = threading.Condition()
        self.imu = {'auth': [], 'nokey': []}
        self.diag = {}
        self.subs = [rospy.Subscriber('/%s/imu' % k, Imu, self.on_imu, callback_args=k, queue_size=10000)
                     for k in ('auth', 'nokey')]
        self.subs.append(rospy.Subscriber('/diagnostics', DiagnosticArray, self.on_diag, queue_size=100))

    def tearDown(self):
        for s in self.subs:
            s.unregister()

    def on_imu(self, msg, key):
        with self.cond:
            self.imu[key].append(msg.linear_acceleration.x)
            self.cond.notify_all()

    def on_diag(self, msg):
        with self.cond:
            for st in msg.status:
                for key in ('auth', 'nokey'):
                    if st.name.startswith(key + ':'):
                        self.diag[key] = (st.level, st.message, {kv.key: kv.value for kv in st.values})
            self.cond.notify_all()

    def wait_for(self, what, predicate):
        with self.cond:
            ok = self.cond.wait_for(predicate, timeout=WAIT_S)
        self.assertTrue(ok, 'waited %.0f s for %s; diagnostics: %s' % (WAIT_S, what, self.diag))

    def value(self, bridge, key):
        return self.diag.get(bridge, (0, '', {}))[2].get(key)

    def test_only_tagged_datagrams_are_published(self):
        self.wait_for('the keyed bridge', lambda: self.value('auth', 'authentication') is not None)
        self.assertEqual(self.value('auth', 'authentication'), 'HMAC-SHA256, key_file ' + self.key_file)
        good, keyless, forger = sender(), sender(), sender()
        dest = ('127.0.0.1', self.ports['auth'])
        # One sample at sequence 0, then the stream jumps ahead to 5000 (a counter may jump ahead).
        first = v2(KEY, 0, 0.0, 100.0)
        good.sendto(first, dest)
        self.wait_for('the first sample', lambda: len(self.imu['auth']) >= 1)
        captured = []
        # The intruders send the same sequence numbers first, with other values.
        for k in range(20):
            seq = 5000 + k
            keyless.sendto(v1(seq, seq * 0.01, -1.0), dest)
            forger.sendto(v2(WRONG_KEY, seq, seq * 0.01, -2.0), dest)
            d = v2(KEY, seq, seq * 0.01, float(k))
            if k == 10:  # altered in transit: one bit of ax
                bad = bytearray(d)
                bad[24] ^= 0x01
                good.sendto(bytes(bad), dest)
            captured.append(d)
            good.sendto(d, dest)
        keyless.sendto(b'50.2,1.0,0.0,0.0\n', dest)  # text carries no tag either
        self.wait_for('21 published samples', lambda: len(self.imu['auth']) >= 21)
        self.wait_for('21 bad tags, 21 unauthenticated',
                      lambda: self.value('auth', 'dropped, bad tag') == '21'
                      and self.value('auth', 'dropped, unauthenticated (no tag)') == '21')
        # The captured datagrams replayed, from another port: valid tags, old sequence numbers. The
        # 20 recent ones are duplicates; sequence 0, more than 4096 behind, is stale (not a restart).
        replayer = sender()
        for d in captured + [first]:
            replayer.sendto(d, dest)
        self.wait_for('20 duplicates and 1 stale',
                      lambda: self.value('auth', 'duplicates (dropped)') == '20'
                      and self.value('auth', 'stale (far behind, with key_file: dropped)') == '1')
        with self.cond:
            self.assertEqual(self.imu['auth'], [100.0] + [float(k) for k in range(20)])
            level, message, values = self.diag['auth']
        g, k, f = (s.getsockname()[1] for s in (good, keyless, forger))
        self.assertEqual(level, DiagnosticStatus.ERROR)
        self.assertEqual(values['published'], '21')
        self.assertEqual(values['samples accepted'], '42')  # 21 good + 21 replays reach the window
        self.assertEqual(values['resyncs (counter restarted)'], '1')  # 0 -> 5000
        self.assertEqual(values['senders unauthenticated'], '127.0.0.1:%d (21)' % k)
        self.assertEqual(values['senders with a bad tag'], ', '.join(
            '127.0.0.1:%d (%d)' % (p, n) for p, n in sorted([(g, 1), (f, 20)])))
        self.assertEqual(values['dropped, version 2 without key_file'], '0')
        self.assertEqual(values['malformed'], '0')
        self.assertIn('datagrams refused by authentication: unauthenticated: 127.0.0.1:%d (21); bad tag: ' % k,
                      message)
        self.assertIn('1 samples far behind the stream dropped (replayed, or the sender\'s counter went back)',
                      message)
        for s in (good, keyless, forger, replayer):
            s.close()

    def test_without_a_key_version_2_is_refused(self):
        self.wait_for('the bridge without a key', lambda: self.value('nokey', 'authentication') is not None)
        self.assertEqual(self.value('nokey', 'authentication'), 'none (no key_file)')
        s = sender()
        dest = ('127.0.0.1', self.ports['nokey'])
        for seq in range(5):
            s.sendto(v2(KEY, seq, seq * 0.01, 3.0), dest)
        s.sendto(v1(5, 0.05, 4.0), dest)  # version 1 is accepted as before
        self.wait_for('the version-1 sample', lambda: len(self.imu['nokey']) >= 1)
        self.wait_for('5 refused', lambda: self.value('nokey', 'dropped, version 2 without key_file') == '5')
        with self.cond:
            self.assertEqual(self.imu['nokey'], [4.0])
            level, message, values = self.diag['nokey']
        self.assertEqual(level, DiagnosticStatus.ERROR)
        self.assertEqual(values['senders of version 2 without key_file'], '127.0.0.1:%d (5)' % s.getsockname()[1])
        self.assertIn('version 2 without key_file: 127.0.0.1:%d (5)' % s.getsockname()[1], message)
        s.close()

    def run_bridge(self, key_file):
        name = 'bad_key_%d' % random.randrange(1 << 30)
        r = subprocess.run(bridge_args(name, free_port(), '_key_file:=' + key_file),
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=30)
        return r.returncode, r.stdout.decode(errors='replace')

    def write(self, name, data, mode):
        path = os.path.join(self.dir, name)
        with open(path, 'wb') as f:
            f.write(data)
        os.chmod(path, mode)
        return path

    def test_bad_key_files_stop_the_node(self):
        missing = os.path.join(self.dir, 'missing.key')
        cases = [
            (missing, "~key_file: key file '%s': No such file or directory" % missing),
            (self.write('empty.key', b'', 0o600), "~key_file: key file '%s' is empty"),
            (self.write('group.key', KEY, 0o640),
             "~key_file: key file '%s' is accessible to group or others (mode 0640): chmod 600 it"),
            (self.write('world.key', KEY, 0o644),
             "~key_file: key file '%s' is accessible to group or others (mode 0644): chmod 600 it"),
        ]
        for path, expected in cases:
            code, out = self.run_bridge(path)
            self.assertEqual(code, 2, out)
            self.assertIn(expected.replace('%s', path), out)


if __name__ == '__main__':
    rospy.init_node('udp_authenticated_test')
    rostest.rosrun('rocking_monitor', 'udp_authenticated', AuthenticatedTest)
