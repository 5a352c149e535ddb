#!/usr/bin/python3
"""rostest: live == offline through the shaking-table path. The Rinaldi Receiving Sta record
(Northridge 1994; x = 318, y = 228 deg as record_to_bag orders them, z = up) is sent to
udp_accel_bridge as binary datagrams from a controller clock starting at 0 s, one sample at a time
(the next once the monitor has published the state of the last); the monitor's alarms and plane
verdicts must equal rocking_sim's on the AT2 files."""
import json
import os
import socket
import struct
import subprocess
import time
import unittest

import roslib.packages
import rospy
import rostest
from rocking_monitor.msg import OverturnAlarm, RockingState, RockingStateArray

G = 9.80665
DT = 0.01
LEVELS = [(OverturnAlarm.BEYOND_TIPPING, 'beyond_tipping'), (OverturnAlarm.COMMITTED, 'committed'),
          (OverturnAlarm.OVERTURNED, 'overturn')]


def read_at2(path):
    with open(path) as f:
        lines = f.read().splitlines()
    npts = int(lines[3].split('NPTS=')[1].split(',')[0])
    return [float(tok) * G for line in lines[4:] for tok in line.split()][:npts]


def exe(name):
    return [p for p in roslib.packages.find_node('rocking_monitor', name) if os.access(p, os.X_OK)][0]


class ShakingTableLiveOffline(unittest.TestCase):
    def test_alarms_equal_rocking_sim(self):
        d = os.path.join(rospy.get_param('~records_dir'), 'northridge_1994')
        if not os.path.isfile(os.path.join(d, 'Rinaldi318.AT2')):
            self.skipTest('records directory not found: ' + d)
        hx, hy, up = (os.path.join(d, f) for f in ('Rinaldi318.AT2', 'Rinaldi228.AT2', 'RinaldiUP.AT2'))
        x, y, z = read_at2(hx), read_at2(hy), read_at2(up)
        n = min(len(x), len(y), len(z))

        # offline, with the monitor's settings
        tol = rospy.get_param('/rocking_monitor/tol', 1e-6)
        fidelity = rospy.get_param('/rocking_monitor/fidelity', 'adaptive')
        items = rospy.get_param('/rocking_monitor/items')
        offline = {}
        for it in items:
            cmd = [exe('rocking_sim'), '--record', hx, '--vertical', up, '--json', '--fidelity', fidelity,
                   '--scene', 'unknown', '--tol', repr(tol), '--width', repr(it['width']), '--cg-height',
                   repr(it['cg_height']), '--eccentricity', repr(it.get('eccentricity', 0.5))]
            for key, opt in (('radius_of_gyration', '--radius-of-gyration'), ('restitution', '--restitution'),
                             ('mu_s', '--mu-s')):
                if key in it:
                    cmd += [opt, repr(it[key])]
            if 'depth' in it:
                cmd += ['--record-y', hy, '--depth', repr(it['depth']), '--eccentricity-y',
                        repr(it.get('eccentricity_y', 0.5))]
            r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=True)
            offline[it['id']] = json.loads(r.stdout)

        # live, one sample at a time
        states = []
        alarms = {}
        repeated = []

        def on_state(m):
            states.append(m)

        def on_alarm(m):
            if m.level in alarms.setdefault(m.item_id, {}):
                repeated.append(m)
            alarms[m.item_id][m.level] = m

        rospy.Subscriber('/rocking_monitor/states', RockingStateArray, on_state, queue_size=100000)
        rospy.Subscriber('/rocking_monitor/alarms', OverturnAlarm, on_alarm, queue_size=1000)
        # the bridge publishes /ground/imu and the monitor subscribes to it; then our subscriptions connect
        deadline = time.time() + 30
        while time.time() < deadline:
            topics = dict(rospy.get_published_topics())
            if '/ground/imu' in topics and '/rocking_monitor/states' in topics:
                break
            time.sleep(0.1)
        time.sleep(2.0)
        sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        port = rospy.get_param('~port')
        for i in range(n):
            sock.sendto(struct.pack('<4sHHQdddd', b'RMAC', 1, 0, i, i * DT, x[i], y[i], z[i]), ('127.0.0.1', port))
            give_up = time.time() + 5.0
            while i > 0 and len(states) < i and time.time() < give_up:  # the first sample only starts the models
                time.sleep(0.0002)
            self.assertTrue(i == 0 or len(states) >= i, 'monitor stopped acknowledging at sample %d' % i)
        time.sleep(0.5)
        self.assertEqual(len(states), n - 1)
        self.assertEqual(repeated, [])
        last = states[-1]

        counts = {'overturned': 0, 'survived': 0, 'x': 0, 'y': 0}
        self.assertEqual(len(last.items), len(items))
        for k, it in enumerate(items):
            j = offline[it['id']]
            item = j['item']
            got = alarms.get(it['id'], {})
            for level, name in LEVELS:
                flag = 'overturned' if name == 'overturn' else name
                self.assertEqual(level in got, item[flag], '%s %s' % (it['id'], flag))
                if item[flag]:
                    self.assertAlmostEqual(got[level].time_since_first_sample, item[name + '_time_s'], delta=1e-9,
                                           msg='%s %s' % (it['id'], flag))
                    self.assertEqual(got[level].plane, item[name + '_plane'], '%s %s' % (it['id'], flag))
            s = last.items[k]
            for plane, state in (('x', s.x), ('y', s.y)):
                if plane == 'y' and s.plane_count == 1:
                    continue
                p = j['planes'][plane]
                self.assertEqual(state.mode == RockingState.OVERTURNED, p['overturned'], '%s %s' % (it['id'], plane))
                self.assertEqual(state.impacts, p['impacts'], '%s %s' % (it['id'], plane))
            if item['overturned']:
                counts['overturned'] += 1
                counts[item['overturn_plane']] += 1
            else:
                counts['survived'] += 1
        # a real test: some fall, some stay, each plane decides some
        self.assertGreater(counts['overturned'], 0)
        self.assertGreater(counts['survived'], 0)
        self.assertGreater(counts['x'], 0)
        self.assertGreater(counts['y'], 0)
        rospy.loginfo('shaking table live == offline: %s', counts)


if __name__ == '__main__':
    rospy.init_node('shaking_table_live_offline')
    rostest.rosrun('rocking_monitor', 'shaking_table_live_offline', ShakingTableLiveOffline)
