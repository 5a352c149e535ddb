#!/usr/bin/python3
"""rostest (test/ros/monitor_pair.test): a redundant pair loses no alarm and delays none (issue 29 part 3).

launch/monitor_pair.launch is started with roslaunch (both machines localhost, each monitor's journal and
snapshot in a scratch folder, respawn="true"), beside a control monitor that is never killed (/pair_ctl,
no journal). The real Rinaldi 228 record is streamed in real time (restamped on the wall clock), in
lock-step with every monitor that is up. ~kill_after s after the control's first item leaves rest, monitor
~kill (a or b) is killed with SIGKILL; roslaunch respawns it and it continues from its state snapshot on
the plain topic (the samples sent meanwhile are lost to it). Checked:
- the killed monitor was respawned (another pid) and says it continues from the state snapshot;
- the alarms as a consumer shows them are the control's: the same (item, level), input stamp (to the
  sample), event time and plane, each shown once; the consumers: scripts/alarm_dedup.py (rocking_report,
  monitor_table.py) over both monitors' ~alarms in arrival order, a dashboard node with ~pair
  (core::AlarmDedup; its /api/snapshot), and the post-event report written by rocking_report --node with
  ~pair (its items table);
- the survivor's alarms are the control's, each (no alarm delayed);
- measured and logged: whether the pair's (event_id, sequence) agree, and the respawned monitor's times.
"""
import os
import signal
import subprocess
import tempfile
import time
import unittest
import urllib.request
import xmlrpc.client

import json

import roslib.packages
import rosgraph
import rosnode
import rospy
import rostest
from rocking_monitor.msg import OverturnAlarm, RockingStateArray
from sensor_msgs.msg import Imu

from alarm_dedup import AlarmDedup
from monitor_journal import Monitor, record_samples, wait_for
from report_check import parse, summary

LEVELS = {2: 'BEYOND_TIPPING', 3: 'COMMITTED', 4: 'OVERTURNED'}
PAIR = {'a': '/rocking_monitor_a', 'b': '/rocking_monitor_b'}


def node_pid(name):
    """The pid of a running node (its XML-RPC getPid), None when it is not up."""
    try:
        uri = rosnode.get_api_uri(rosgraph.Master('/monitor_pair_test'), name, skip_cache=True)
        if not uri:
            return None
        code, _, pid = xmlrpc.client.ServerProxy(uri).getPid('/monitor_pair_test')
        return pid if code == 1 else None
    except (OSError, xmlrpc.client.Error, rosnode.ROSNodeIOException):
        return None


class PairMember:
    """What this test received from one monitor of the pair (across its respawns)."""

    def __init__(self, name, received):
        self.name = name
        self.alarms = []
        self.acked = 0.0
        self.received = received  # (source, alarm) in arrival order, shared by both
        self.sub_a = rospy.Subscriber(name + '/alarms', OverturnAlarm, self._alarm, queue_size=1000)
        self.sub_s = rospy.Subscriber(name + '/states', RockingStateArray, self._state, queue_size=1000)

    def _alarm(self, m):
        self.alarms.append(m)
        self.received.append((self.name, m))

    def _state(self, m):
        self.acked = m.header.stamp.to_sec()


def row_key(m):
    return (m.item_id, m.level, m.header.stamp.to_nsec(), m.event_time, m.plane)


class Pair(unittest.TestCase):
    def test_kill_one_of_the_pair_during_strong_motion(self):
        path = os.path.join(rospy.get_param('~records'), rospy.get_param('~record'))
        if not os.path.exists(path):
            print('NOTICE: record not found (%s): pair test skipped' % path)
            self.skipTest('record not found')
        which = rospy.get_param('~kill')
        self.assertIn(which, PAIR)
        kill_after = rospy.get_param('~kill_after')
        scratch = tempfile.mkdtemp(prefix='rocking_pair_')
        samples = record_samples(self, path, scratch)
        t0 = samples[0].header.stamp
        offsets = [m.header.stamp - t0 for m in samples]
        imu = rospy.Publisher('/ground/imu', Imu, queue_size=4000)

        control = Monitor('pair_ctl', os.path.join(scratch, 'control.log'))
        self.addCleanup(control.close)  # also when an assertion fails
        def start(cmd, log_name, stop_timeout):
            """A process of the test with its output in the scratch folder, stopped by SIGINT at the end."""
            log = open(os.path.join(scratch, log_name), 'w')
            proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT)

            def stop():
                if proc.poll() is None:
                    proc.send_signal(signal.SIGINT)
                    try:
                        proc.wait(timeout=stop_timeout)
                    except subprocess.TimeoutExpired:
                        proc.kill()
                log.close()

            self.addCleanup(stop)
            return proc, log

        _, launch_log = start(
            ['roslaunch', 'rocking_monitor', 'monitor_pair.launch', 'journal_a:=' + os.path.join(scratch, 'a.jsonl'),
             'journal_b:=' + os.path.join(scratch, 'b.jsonl'), 'params:=' + rospy.get_param('~params'),
             'state_rate:=0.0', 'state_queue_size:=100000'],  # own arguments: a <param> beats the params file
            'pair.log', 30)

        def launch_text():
            launch_log.flush()
            with open(launch_log.name) as f:
                return f.read()

        # The dashboard of the pair, as an operator runs it: ~monitor a, ~pair b.
        dash_exe = [p for p in roslib.packages.find_node('rocking_monitor', 'dashboard') if os.access(p, os.X_OK)][0]
        start([dash_exe, '__name:=pair_dashboard', '_port:=0', '_monitor:=' + PAIR['a'], '_pair:=' + PAIR['b']],
              'dashboard.log', 20)
        # The post-event report of the pair, written by the node when the event ends.
        reports = os.path.join(scratch, 'reports')
        report_exe = [p for p in roslib.packages.find_node('rocking_monitor', 'rocking_report') if os.access(p, os.X_OK)][0]
        start([report_exe, '--node', '__name:=pair_report', '_report_dir:=' + reports,
               '_monitor:=' + PAIR['a'], '_pair:=' + PAIR['b']], 'report.log', 20)
        received = []
        members = {k: PairMember(n, received) for k, n in PAIR.items()}
        moving = control.moving  # input stamp at which the control's first item left rest
        wait_for('the control and the pair', lambda: imu.get_num_connections() >= 3 and all(
            s.get_num_connections() > 0 for s in [control.sub_s] + [m.sub_s for m in members.values()]
            + [m.sub_a for m in members.values()]), timeout=60.0)
        wait_for('the dashboard', lambda: rospy.has_param('/pair_dashboard/url'), timeout=30.0)
        dash_url = rospy.get_param('/pair_dashboard/url')

        def dashboard_subscribed():
            subs = dict((t, n) for t, n in rosgraph.Master('/monitor_pair_test').getSystemState()[1])
            return all(node in subs.get(n + '/alarms', []) for n in PAIR.values()
                       for node in ('/pair_dashboard', '/pair_report'))

        wait_for('the dashboard and the report subscribed to both monitors\' alarms', dashboard_subscribed,
                 timeout=30.0)
        time.sleep(1.0)
        pid_before = node_pid(PAIR[which])
        self.assertIsNotNone(pid_before, launch_text()[-3000:])

        # The stream in real time, in lock-step with the monitors up (from the second sample on).
        killed = members[which]
        live = [control] + list(members.values())
        state = {'killed_at': None, 'back_at': None, 'killed_wall': None, 'back_wall': None, 'kill_stamp': None}
        base = rospy.Time.now() + rospy.Duration(0.05)
        for i, m in enumerate(samples):
            m.header.stamp = base + offsets[i]
            stamp = m.header.stamp.to_sec()
            while rospy.Time.now().to_sec() < stamp:
                time.sleep(0.0005)
            imu.publish(m)
            if i > 0:
                deadline = time.time() + 30.0  # lock-step: a loaded machine may take long (issue 42)
                while any(mon.acked < stamp - 1e-6 for mon in live) and time.time() < deadline:
                    time.sleep(0.0002)
            if state['killed_at'] is None and moving and stamp >= moving[0] + kill_after:
                os.kill(pid_before, signal.SIGKILL)
                state['killed_at'] = i
                state['killed_wall'] = time.time()
                state['kill_stamp'] = stamp  # states of the killed process still queued are not newer
                killed.acked = 0.0
                live = [mon for mon in live if mon is not killed]
            elif state['killed_at'] is not None and state['back_at'] is None and killed.acked > state['kill_stamp']:
                state['back_at'] = i  # the respawned monitor steps again: in lock-step from now on
                state['back_wall'] = time.time()
                live.append(killed)
        time.sleep(1.0)
        self.assertIsNotNone(state['killed_at'], 'no item of the control left rest: ' + control.text()[-2000:])
        self.assertIsNotNone(state['back_at'], 'the killed monitor never came back:\n' + launch_text()[-3000:])
        pid_after = node_pid(PAIR[which])
        self.assertNotIn(pid_after, (None, pid_before), 'not respawned')
        text = launch_text()
        self.assertIn('continue from the state snapshot', text, text[-3000:])
        k, b = state['killed_at'], state['back_at']
        when = ('monitor %s killed at sample %d (%.3f s into the record, %.2f s after the first item left rest); '
                'respawned, stepping again from sample %d (%.2f s of wall time later)' % (
                    which, k, offsets[k].to_sec(), kill_after, b, state['back_wall'] - state['killed_wall']))
        rospy.loginfo(when)
        print(when)

        ctl = sorted(row_key(m) for m in control.alarms)
        self.assertGreater(len(ctl), 0)
        survivor = members['b' if which == 'a' else 'a']

        # As a consumer shows them: both monitors' alarms, in the order received, deduplicated.
        dedup = AlarmDedup()
        for source, m in received:
            dedup.add(source, m)
        shown = sorted(row_key(m) for m in dedup.alarms())

        # The measurement: what the pair's own numbering would have given, and the respawned one's times.
        def rel(m):
            return m.event_time - base.to_sec()

        by_key = {}
        for name, mem in members.items():
            for m in mem.alarms:
                by_key.setdefault((m.item_id, m.level), {}).setdefault(name, []).append(m)
        ctl_by = {(m.item_id, m.level): m for m in control.alarms}
        rows, ids_differ = [], 0
        for kk in sorted(set(by_key) | set(ctl_by)):
            got = by_key.get(kk, {})
            a = got.get('a', [None])[0]
            bb = got.get('b', [None])[0]
            c = ctl_by.get(kk)
            if a and bb and (a.event_id, a.sequence) != (bb.event_id, bb.sequence):
                ids_differ += 1
            rows.append('%-18s %-15s control %7s  a %7s %-28s %5s  b %7s %-28s %5s' % (
                kk[0], LEVELS[kk[1]], '%.3f' % rel(c) if c else '-', '%.3f' % rel(a) if a else '-',
                '%s#%d' % (a.event_id, a.sequence) if a else '', '%.2f' % a.frozen_s if a else '',
                '%.3f' % rel(bb) if bb else '-', '%s#%d' % (bb.event_id, bb.sequence) if bb else '',
                '%.2f' % bb.frozen_s if bb else ''))
        report = ('alarms, s since the stream began (control; a and b with event_id#sequence and frozen_s); %d '
                  'received, %d shown, %d merged across the pair (%d shown instead of the copy first received), %d '
                  'repeats dropped; (event_id, sequence) differ between a and b for %d alarms:\n' % (
                      len(received), len(dedup.rows()), dedup.merged, dedup.replaced, dedup.repeats, ids_differ)
                  + '\n'.join(rows))
        rospy.loginfo(report)
        print(report)

        # The dashboard's alarm log (core::AlarmDedup): the same alarms, each once.
        with urllib.request.urlopen(dash_url.rstrip('/') + '/api/snapshot', timeout=30) as r:
            snap = json.loads(r.read().decode())
        names = {v: k for k, v in LEVELS.items()}
        dash_rows = sorted((a['item'], names[a['level']], a['event_time'], a['plane']) for a in snap['alarms'])
        ctl_rows = sorted((m.item_id, m.level, m.event_time, m.plane) for m in control.alarms)
        dash_stamps = sorted((a['item'], names[a['level']], a['stamp']) for a in snap['alarms'])
        print('dashboard: %d alarms shown, copies not shown: %s' % (len(dash_rows), snap.get('alarm_copies')))
        self.assertEqual(dash_rows, ctl_rows, report)
        for (item, level, st), m in zip(dash_stamps, sorted(control.alarms, key=lambda m: (m.item_id, m.level))):
            self.assertEqual((item, level), (m.item_id, m.level))
            self.assertAlmostEqual(st, m.header.stamp.to_sec(), delta=1e-6)  # the same sample (10 ms apart)

        # The field the rule ranks by: the survivor's alarms came from every sample; the respawned one's
        # live alarms (stamped after its gap) say how long its items were frozen, about the restart's length.
        self.assertTrue(all(m.frozen_s == 0.0 for m in survivor.alarms), report)
        gap_s = (offsets[b] - offsets[k]).to_sec()
        for m in killed.alarms:
            if m.header.stamp.to_sec() > base.to_sec() + offsets[b].to_sec():
                self.assertGreater(m.frozen_s, 0.0, report)
                self.assertLess(m.frozen_s, gap_s + 0.12, report)  # + the snapshot's age (<= 0.1 s) + a sample

        # The post-event report's items table (alarm_dedup.py over the event's bag): the control's alarms, at
        # its times since the first sample (the survivor's clock and the control's start on the same sample).
        wait_for('the post-event report', lambda: any(f.endswith('.html') for f in os.listdir(reports))
                 if os.path.isdir(reports) else False, timeout=60.0)
        page = sorted(os.path.join(reports, f) for f in os.listdir(reports) if f.endswith('.html'))[0]
        with open(page, encoding='utf-8') as f:
            self.assertIn('id="pair"', f.read())
        table = summary(parse(page))
        in_report = sorted((item, level, round(v[0], 6), v[1]) for item, d in table.items()
                           for level, v in d.items() if level in names and v is not None)
        in_control = sorted((m.item_id, LEVELS[m.level], round(m.time_since_first_sample, 6), m.plane)
                            for m in control.alarms)
        print('report %s: %d alarms in its items table' % (os.path.basename(page), len(in_report)))
        self.assertEqual(in_report, in_control, report)

        # No alarm delayed: the survivor never stopped, its alarms are the control's to the bit.
        self.assertEqual(sorted(row_key(m) for m in survivor.alarms), ctl, report)
        # Each alarm shown once, at the control's sample and time: nothing lost, late or doubled.
        self.assertEqual(shown, ctl, report)
        launch_log.flush()


if __name__ == '__main__':
    rospy.init_node('monitor_pair_test')
    rostest.rosrun('rocking_monitor', 'monitor_pair', Pair)
