#!/usr/bin/python3
"""rostest (test/ros/monitor_restart.test): a monitor killed during the strong motion continues from its
state snapshot (issue 29).

The real Rinaldi 228 record is streamed in real time (restamped on the wall clock) to the example
catalogue's monitor (/restart_mon, journal and snapshot in a scratch folder) and to a control that is
never killed (/restart_ctl). ~kill_after s after the control's first item leaves rest the monitor is
killed with SIGKILL and a new one started at once on the same files; the stream goes on meanwhile (the
samples it misses are lost, as on a plain topic). Checked:
- the restarted monitor says it continues from the snapshot, with the gap;
- ~catch_up true (what a bridge's history gives): the restarted monitor is sent the last 0.5 s again and
  then the rest faster than real time: every (item, level) the control alarms is alarmed by the killed or
  the restarted monitor at exactly the control's event time;
- ~catch_up false (a plain topic: the samples sent during the restart are lost, a frozen gap): every
  (item, level) is alarmed; the differences of the times are logged (the measurement);
- ~catch_up_service naming a service that is not there (issue 29 part 2): the restarted monitor says so
  and falls back to the frozen gap;
- no (item, level) is alarmed twice;
- a damaged and a foreign snapshot are each refused at start with the reason, the items at rest.
"""
import os
import signal
import subprocess
import tempfile
import time
import unittest

import rospy
import rostest
from sensor_msgs.msg import Imu

from monitor_journal import Monitor, key, record_samples, wait_for

LEVELS = {2: 'BEYOND_TIPPING', 3: 'COMMITTED', 4: 'OVERTURNED'}


class Restart(unittest.TestCase):
    def test_kill_during_strong_motion_resumes_from_snapshot(self):
        path = os.path.join(rospy.get_param('~records'), rospy.get_param('~record'))
        if not os.path.exists(path):
            print('NOTICE: record not found (%s): restart test skipped' % path)
            self.skipTest('record not found')
        kill_after = rospy.get_param('~kill_after')
        catch_up = rospy.get_param('~catch_up')
        back = 0.5  # s sent again after the restart (catch_up)
        lost = 0.3  # s sent to the control alone while the monitor restarts (no catch_up)
        scratch = tempfile.mkdtemp(prefix='rocking_restart_')
        samples = record_samples(self, path, scratch)
        t0 = samples[0].header.stamp
        offsets = [m.header.stamp - t0 for m in samples]
        journal = os.path.join(scratch, 'journal.jsonl')
        snapshot = os.path.join(scratch, 'journal.snapshot')
        rospy.set_param('/restart_mon/journal', journal)
        imu = rospy.Publisher('/ground/imu', Imu, queue_size=4000)

        control = Monitor('restart_ctl', os.path.join(scratch, 'control.log'))
        self.addCleanup(control.close)  # also when an assertion fails
        first = Monitor('restart_mon', os.path.join(scratch, 'monitor1.log'))
        self.addCleanup(first.close)  # also when an assertion fails
        moving = control.moving  # input stamp at which the control's first item left rest
        wait_for('both monitors', lambda: imu.get_num_connections() >= 2 and first.sub_s.get_num_connections() > 0
                 and control.sub_s.get_num_connections() > 0)
        time.sleep(0.5)

        # The stream, in real time, in lock-step with the monitors listed in `live` (from the second sample).
        live = [control, first]
        state = {'killed_at': None, 'second': None, 'joined_at': None}
        base = rospy.Time.now() + rospy.Duration(0.05)
        dt = (offsets[1] - offsets[0]).to_sec()
        i = 0
        while i < len(samples):
            m = samples[i]
            m.header.stamp = base + offsets[i]
            stamp = m.header.stamp.to_sec()
            while rospy.Time.now().to_sec() < stamp:
                time.sleep(0.0005)
            imu.publish(m)
            replaying = state['killed_at'] is not None and i <= state['killed_at'] and catch_up
            if replaying:
                time.sleep(0.0005)  # samples the restarted monitor is sent again: it drops those before its snapshot
            elif i > 0:
                deadline = time.time() + 30.0  # lock-step: a loaded machine may take long (issue 42)
                while any(mon.acked < stamp - 1e-6 for mon in live) and time.time() < deadline:
                    time.sleep(0.0002)
            if state['killed_at'] is None and moving and stamp >= moving[0] + kill_after:
                os.kill(first.proc.pid, signal.SIGKILL)
                state['killed_at'] = i
                live = [control]
                first.proc.wait(timeout=30)
                # A plain topic loses what is sent while the monitor restarts. The loss is the test's to set,
                # not the machine's: `lost` s of samples go to the control alone, then the stream waits for
                # the restarted monitor (at load 10 its start took 1.6 s of wall clock, beyond ~max_bridge,
                # issue 42). The stamps then run behind the wall clock until caught up: lag, not a gap.
                state['start_second_at'] = i if catch_up else i + int(round(lost / dt))
            if state.get('start_second_at') == i:
                state['start_second_at'] = None  # once (catch_up sends samples again from before i)
                second = Monitor('restart_mon', os.path.join(scratch, 'monitor2.log'))
                self.addCleanup(second.close)  # also when an assertion fails
                state['second'] = second
                wait_for('the restarted monitor', lambda: imu.get_num_connections() >= 2 and
                         second.sub_s.get_num_connections() > 0)
                if catch_up:
                    # As a bridge's history would: the restarted monitor is sent the last `back` s again (more
                    # than a snapshot period), then the stream goes on, faster than real time until caught up.
                    state['joined_at'] = i + 1
                    live = [control, second]
                    i = max(1, i - int(round(back / dt)))
                    continue
            second = state['second']
            if second is not None and state['joined_at'] is None and second.acked > 0.0:
                state['joined_at'] = i  # stepping again: from now on in lock-step too
                live = [control, second]
            i += 1
        time.sleep(1.0)
        self.assertIsNotNone(state['killed_at'], 'no item of the control left rest: ' + control.text()[-2000:])
        second = state['second']
        self.assertEqual(first.proc.returncode, -signal.SIGKILL)
        k = state['killed_at']
        rospy.loginfo('killed at sample %d (%.3f s into the record, %.2f s after the first item left rest); the '
                      'restarted monitor stepped again from sample %s', k, offsets[k].to_sec(), kill_after,
                      state['joined_at'])
        log2 = second.text()
        self.assertIn('continue from the state snapshot', log2, log2[-3000:])

        # The killed and the restarted monitor together against the control.
        ctl = {key(m): m for m in control.alarms}
        got = {}
        for m in first.alarms + second.alarms:
            if key(m) in got:  # re-sent from the journal by the restarted one: the same alarm
                self.assertEqual((m.event_id, m.sequence, m.event_time),
                                 (got[key(m)].event_id, got[key(m)].sequence, got[key(m)].event_time))
                continue
            got[key(m)] = m
        rows = []
        for kk in sorted(set(ctl) | set(got)):
            a, b = ctl.get(kk), got.get(kk)
            diff = (b.event_time - a.event_time) if a and b else float('nan')
            rows.append('%-18s %-15s control %s restarted pair %s  diff %+.3f s' % (
                kk[0], LEVELS[kk[1]], '%.3f' % (a.event_time - t0.to_sec() - (base - t0).to_sec()) if a else '-',
                '%.3f' % (b.event_time - t0.to_sec() - (base - t0).to_sec()) if b else '-', diff))
        rospy.loginfo('alarms (s into the record), control vs the killed + restarted monitor:\n' + '\n'.join(rows))
        print('\n'.join(rows))
        self.assertGreater(len(ctl), 0)
        if catch_up:
            # Nothing missed: the restarted monitor continues exactly where the snapshot left off.
            self.assertRegex(log2, r'its last sample is 0\.[0-9]+ s after this one, 0 samples missing')
            self.assertEqual(sorted(got), sorted(ctl), 'the (item, level) alarmed differ:\n' + '\n'.join(rows))
            for kk, a in ctl.items():
                self.assertEqual((got[kk].event_time, got[kk].plane), (a.event_time, a.plane), '\n'.join(rows))
        else:
            # A plain topic: what was sent while the monitor restarted is lost (a gap, frozen). The items'
            # motion then differs from the control's (rocking is chaotic): every level is still alarmed
            # when the kill comes early in the shaking; the times are logged, not bounded (measured in
            # docs/journal.md: up to 2.4 s late for an item that rocked through the gap).
            self.assertRegex(log2, r'its last sample is 0\.[0-9]+ s before this one, [0-9]+ samples missing')
            if rospy.get_param('~catch_up_service'):  # a bridge without history (or none): said, then the gap
                self.assertIn('not caught up from %s: the service is not there' % rospy.get_param('~catch_up_service'),
                              log2)
            self.assertEqual(sorted(got), sorted(ctl), 'the (item, level) alarmed differ:\n' + '\n'.join(rows))
        first.close()
        second.close()
        control.close()

        # The snapshot refused at start, each time with its reason: damaged, foreign, stale.
        with open(snapshot, 'rb') as f:
            good = f.read()
        damaged = bytearray(good)
        damaged[200] ^= 0x20
        with open(snapshot, 'wb') as f:
            f.write(damaged)
        third = Monitor('restart_mon', os.path.join(scratch, 'monitor3.log'))
        self.addCleanup(third.close)  # also when an assertion fails
        wait_for('the refusal of a damaged snapshot', lambda: 'state snapshot refused' in third.text(), timeout=15.0)
        self.assertIn('%s: payload checksum mismatch: the file is damaged' % snapshot, third.text())
        third.close()
        # Foreign: this catalogue's snapshot given to a monitor of another (the journal test's).
        with open(snapshot, 'wb') as f:
            f.write(good)
        rospy.set_param('/restart_other/journal', os.path.join(scratch, 'other.jsonl'))
        rospy.set_param('/restart_other/snapshot', snapshot)
        subprocess.run(['rosparam', 'load', os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                         'monitor_journal.yaml'), '/restart_other'], check=True)
        other = Monitor('restart_other', os.path.join(scratch, 'monitor4.log'))
        self.addCleanup(other.close)  # also when an assertion fails
        wait_for('the refusal of a foreign snapshot', lambda: 'state snapshot refused' in other.text(), timeout=15.0)
        self.assertIn("%s: foreign: sensor 1 is 'ground_floor', this catalogue's is 'floor'" % snapshot, other.text())
        other.close()
        # Stale: the right snapshot, but the stream resumes long after its last sample (> ~max_bridge).
        fifth = Monitor('restart_mon', os.path.join(scratch, 'monitor5.log'))
        self.addCleanup(fifth.close)  # also when an assertion fails
        wait_for('the fifth monitor', lambda: imu.get_num_connections() >= 1 and fifth.sub_s.get_num_connections() > 0)
        time.sleep(0.5)
        for n in range(5):
            m = samples[0]
            m.header.stamp = rospy.Time.now()
            imu.publish(m)
            time.sleep(0.01)
        wait_for('the refusal of a stale snapshot', lambda: 'state snapshot' in fifth.text() and 'stale' in fifth.text(),
                 timeout=15.0)
        self.assertRegex(fifth.text(), r"sensor 'ground_floor': stale: its last sample is [0-9.]+ s before this one "
                                       r"\(more than ~max_bridge 1\.0+ s\); its 6 items start at rest")
        fifth.close()


if __name__ == '__main__':
    rospy.init_node('monitor_restart_test')
    rostest.rosrun('rocking_monitor', 'monitor_restart', Restart)
