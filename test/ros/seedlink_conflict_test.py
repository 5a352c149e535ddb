#!/usr/bin/python3
"""rostest (issue 52 item 3, SeedLink side): a record that overlaps an earlier one with other samples,
through the SeedLink test server and seedlink_bridge end to end.

The bundled one-sine pulse (bags/one_sine_pulse.csv) as three AT2 components, written by
record_to_mseed as int32 records; the test server (--conflict-at 2) sends packet 1 (the first HNN
record) and then, as packet 2, the same record with every sample 1000 counts larger. Those times are
not yet published (HNE and HNZ come after), so the bridge must keep the first values, count each
differing sample, publish those samples marked (linear_acceleration_covariance diagonal +inf) and turn
the station's /diagnostics ERROR. Every wait is a condition with a hang guard, never a verdict."""
import math
import os
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

WAIT_S = 60.0  # a hang guard on a loaded machine, never a verdict
GAIN = 427000.0  # counts per m/s^2
NODE = 'sl_conflict'


def node_path(name):
    return [p for p in roslib.packages.find_node('rocking_monitor', name) if os.access(p, os.X_OK)][0]


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(('127.0.0.1', 0))
        return s.getsockname()[1]


def write_pulse_at2(folder):
    """The pulse as three PEER AT2 files (g): north the pulse, east half of it, up zero."""
    csv = os.path.join(roslib.packages.get_pkg_dir('rocking_monitor'), 'bags', 'one_sine_pulse.csv')
    values = [float(line.split(',')[1]) for line in open(csv) if line[:1].isdigit()]
    paths = []
    for comp, scale in (('000', 1.0), ('090', 0.5), ('UP', 0.0)):
        path = os.path.join(folder, 'PLS_%s.AT2' % comp)
        with open(path, 'w') as f:
            f.write('PEER NGA STRONG MOTION DATABASE RECORD\nSynthetic pulse, 1/1/2000, TEST, %s\n'
                    'ACCELERATION TIME SERIES IN UNITS OF G\nNPTS= %d, DT= .0050 SEC\n' % (comp, len(values)))
            f.writelines('%.7e\n' % (v * scale / 9.80665) for v in values)
        paths.append(path)
    return paths


def first_record(mseed):
    """Channel and int32 samples of the file's first 512-byte record."""
    rec = open(mseed, 'rb').read(512)
    nsamp = struct.unpack('>H', rec[30:32])[0]
    begin = struct.unpack('>H', rec[44:46])[0]
    return rec[15:18].decode(), struct.unpack('>%di' % nsamp, rec[begin:begin + 4 * nsamp])


class SeedLinkConflict(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix='seedlink_conflict_')
        cls.mseed = os.path.join(cls.dir, 'pulse.mseed')
        subprocess.run([node_path('record_to_mseed'), '--file'] + write_pulse_at2(cls.dir) +
                       ['-o', cls.mseed, '--gain', str(GAIN), '--encoding', 'int32', '--network', 'XX',
                        '--station', 'PLS', '-q'], check=True, timeout=120)
        cls.port = free_port()
        cls.server = None
        # The bridge first: the server starts once this test listens, so no sample is missed.
        cls.bridge = subprocess.Popen([node_path('seedlink_bridge'), '__name:=' + NODE,
                                       '_server:=127.0.0.1:%d' % cls.port, '_streams:=XX_PLS:HN?',
                                       '_gain:=%r' % GAIN, '_backoff_min:=0.2', '_backoff_max:=0.5'])

    @classmethod
    def tearDownClass(cls):
        for p in (cls.bridge, cls.server):
            if p:
                p.terminate()
                p.wait(timeout=30)
        shutil.rmtree(cls.dir, ignore_errors=True)

    def setUp(self):
        self.cond = threading.Condition()
        self.published = []  # (north m/s^2, marked) of every Imu, in order
        self.station = None  # (level, message, values) of the station's status
        self.imu_sub = rospy.Subscriber('/%s/XX_PLS/imu' % NODE, Imu, self.on_imu, queue_size=10000)
        self.diag_sub = rospy.Subscriber('/diagnostics', DiagnosticArray, self.on_diag, queue_size=100)

    def on_imu(self, msg):
        with self.cond:
            self.published.append((msg.linear_acceleration.y, math.isinf(msg.linear_acceleration_covariance[4])))
            self.cond.notify_all()

    def on_diag(self, msg):
        with self.cond:
            for st in msg.status:
                if st.name.startswith(NODE + ':') and 'seedlink station' in st.name:
                    self.station = (st.level, st.message, {kv.key: kv.value for kv in st.values})
            self.cond.notify_all()

    def wait_for(self, what, predicate):
        with self.cond:
            ok = self.cond.wait_for(predicate, timeout=WAIT_S)
        self.assertTrue(ok, 'waited %.0f s for %s; station: %s' % (WAIT_S, what, self.station))

    def test_an_overlap_with_other_values_is_kept_first_marked_and_an_error(self):
        channel, counts = first_record(self.mseed)
        self.assertEqual(channel, 'HNN')  # the record the server copies; its samples are the north axis
        self.assertTrue(any(counts), 'the first record holds the pulse')
        self.wait_for('the bridge to publish and report', lambda: self.imu_sub.get_num_connections() > 0 and
                      self.station is not None)
        type(self).server = subprocess.Popen(
            ['/usr/bin/python3', os.path.join(os.path.dirname(os.path.abspath(__file__)), 'seedlink_test_server.py'),
             '--port', str(self.port), '--speed', '4', '--clock-file', os.path.join(self.dir, 'clock'),
             '--conflict-at', '2', self.mseed])
        n = len(counts)
        value = lambda key: int(self.station[2].get(key, '0'))
        self.wait_for('%d conflicts marked and the samples after them' % n, lambda: len(self.published) > n and
                      value('conflicts marked on the published sample (variance inf)') == n)
        with self.cond:
            published = list(self.published)
            level, message, values = self.station
        self.assertEqual([m for _, m in published[:n + 1]], [True] * n + [False])
        # the first record's values, not the copy's (1000 counts more)
        for (north, _), c in zip(published[:n], counts):
            self.assertAlmostEqual(north, c / GAIN, delta=1e-9)
        self.assertEqual(level, DiagnosticStatus.ERROR, message)
        self.assertIn('%d samples sent again with other values' % n, message)
        self.assertEqual(int(values['overlap conflicts (other values; first kept)']), n)


if __name__ == '__main__':
    rospy.init_node('seedlink_conflict_test')
    rostest.rosrun('rocking_monitor', 'seedlink_conflict', SeedLinkConflict)
