#!/usr/bin/python3
"""rostest: the dashboard page in headless Chromium after the pulse replay.

Loads the page (with ?poll=1: a headless browser's virtual time never runs out while an event stream
is open, so the page polls the snapshot instead) and checks the DOM: every catalogue item has a row
carrying its id and mode, the item that overturned is OVERTURNED, the one that survives is not, and the
red banner is shown, the input acceleration chart holds the pulse, and at a 1280-pixel window the alarm
log's "predicted by" column is not cut. Saves a screenshot (~screenshot, default $ROS_HOME/dashboard_browser.png)."""
import os
import re
import shutil
import subprocess
import tempfile
import time
import unittest

import rospy
import rostest
from rocking_monitor.msg import OverturnAlarm, RockingStateArray

FLAGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
         '--disable-background-networking', '--disable-component-update', '--disable-sync',
         '--virtual-time-budget=5000']


def chromium(args, timeout=90):
    with tempfile.TemporaryDirectory() as profile:
        return subprocess.run(['chromium'] + FLAGS + ['--user-data-dir=' + profile] + args,
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, timeout=timeout, check=True).stdout


class DashboardBrowser(unittest.TestCase):
    def test_overturned_item_shows_as_overturned(self):
        self.assertIsNotNone(shutil.which('chromium'), 'chromium not installed (scripts/install_deps.sh)')
        must_overturn = rospy.get_param('~must_overturn')
        must_survive = rospy.get_param('~must_survive')
        last = {'states': None, 'time': time.time(), 'alarms': [], 'causes': {}}
        rospy.Subscriber('/rocking_monitor/states', RockingStateArray,
                         lambda m: last.update(states=m, time=time.time()), queue_size=10)

        def on_alarm(m):
            last['alarms'].append((m.item_id, m.level))
            last['causes'][(m.item_id, m.level)] = m.cause
        rospy.Subscriber('/rocking_monitor/alarms', OverturnAlarm, on_alarm, queue_size=1000)
        deadline = time.time() + 90
        while not rospy.has_param('/dashboard/url'):
            self.assertLess(time.time(), deadline, 'no /dashboard/url')
            time.sleep(0.1)
        url = rospy.get_param('/dashboard/url')
        # After the replay: the overturn seen on ROS and no state for 2 s (the bag is over).
        while not ((must_overturn, OverturnAlarm.OVERTURNED) in last['alarms'] and time.time() - last['time'] > 2.0):
            self.assertLess(time.time(), deadline, 'replay did not end with %s overturned' % must_overturn)
            time.sleep(0.1)

        # At a 1280-pixel window: the alarm log must be readable there (checked below).
        dom = chromium(['--window-size=1280,1000', '--dump-dom', url + '?poll=1']).decode('utf-8', 'replace')
        rows = {}
        for tag in re.findall(r'<tr [^>]*>', dom):  # item rows carry data-item and data-mode (alarm rows: data-level)
            item, mode = re.search(r'data-item="([^"]+)"', tag), re.search(r'data-mode="([^"]+)"', tag)
            if item and mode:
                rows[item.group(1)] = mode.group(1)
        ids = [s.id for s in last['states'].items]
        for i in ids:
            self.assertIn(i, rows, 'no row for %s in the DOM' % i)
        modes = {s.id: s.mode for s in last['states'].items}
        names = ['REST', 'ROCKING', 'BEYOND_TIPPING', 'COMMITTED', 'OVERTURNED']
        for i in ids:
            self.assertEqual(rows[i], names[modes[i]], i)
        self.assertEqual(rows[must_overturn], 'OVERTURNED')
        self.assertNotEqual(rows[must_survive], 'OVERTURNED')
        self.assertRegex(dom, r'<div id="banner" role="alert">[^<]*' + must_overturn)
        # The input acceleration chart (sensor health panel) holds the pulse: its peak 4.0 m/s^2 survives
        # the 50 ms bins.
        chart = re.search(r'<canvas id="input-chart"[^>]*>', dom)
        self.assertIsNotNone(chart, 'no input chart in the DOM')
        points, peak = re.search(r'data-points="(\d+)"', chart.group(0)), re.search(r'data-peak="([^"]+)"', chart.group(0))
        self.assertIsNotNone(points, 'input chart never drawn: %s' % chart.group(0))
        self.assertGreater(int(points.group(1)), 100)
        self.assertAlmostEqual(float(peak.group(1)), 4.0, delta=1e-6)
        # The alarm log's last column ("predicted by") shows whole without scrolling at 1280 px: alarms.js
        # records on the table where the column lies and what of the log is visible (markAlarmLayout).
        alarm_rows = re.findall(r'<tr data-item="[^"]+" data-level="[^"]+">', dom)
        self.assertGreater(len(alarm_rows), 0, 'no alarm rows in the DOM')
        table = re.search(r'<table id="alarms"[^>]*>', dom)
        self.assertIsNotNone(table, 'no alarm log in the DOM')
        layout = dict(re.findall(r'data-([a-z-]+)="([^"]*)"', table.group(0)))
        self.assertIn('last-column', layout, 'alarm log layout never recorded: %s' % table.group(0))
        # the window really was 1280 px wide (less a vertical scrollbar)
        self.assertGreater(int(layout['viewport']), 1200, layout)
        self.assertLessEqual(int(layout['viewport']), 1280, layout)
        col_left, col_right = map(int, layout['last-column'].split(','))
        vis_left, vis_right = map(int, layout['visible'].split(','))
        self.assertGreater(col_right - col_left, 50, 'the "predicted by" column has no width: %s' % layout)
        self.assertGreaterEqual(col_left, vis_left, layout)
        self.assertLessEqual(col_right, vis_right,
                             'the alarm log\'s "predicted by" column is cut at 1280 px: %s' % layout)
        print('DOM rows: %s; alarm log at 1280 px: %s' % (rows, layout))

        # An item the 3-D model decides (~solid: its id; the catalogue gives it a base polygon): selected,
        # its detail says so, with the tilt it ended at and the alarms' plane "3d".
        solid = rospy.get_param('~solid', '')
        if solid:
            state = [s for s in last['states'].items if s.id == solid][0]
            self.assertEqual(state.model, 'rocking_3d')
            detail = chromium(['--window-size=1280,1000', '--dump-dom', url + '?poll=1&select=' + solid]).decode('utf-8', 'replace')
            self.assertIn('<td>model</td><td>rocking_3d</td>', detail)
            tilt = re.search(r'<td>tilt, contact</td><td>([0-9.]+) rad, ([^<]+)</td>', detail)
            self.assertIsNotNone(tilt, 'no tilt row in the detail of %s' % solid)
            self.assertAlmostEqual(float(tilt.group(1)), state.tilt, delta=1e-4)
            self.assertRegex(detail, r'<tr data-item="%s" data-level="[^"]+">(?:(?!</tr>).)*<td>3d</td>' % re.escape(solid))
            print('3-D item %s: tilt %s rad, %s' % (solid, tilt.group(1), tilt.group(2)))

        # An item that slid off its plinth (~fell_off: its id; issue 51): its OVERTURNED alarm has the cause
        # on ROS and in the alarm log, the rocked item's has not; its detail gives the support margin.
        fell_off = rospy.get_param('~fell_off', '')
        if fell_off:
            self.assertEqual(last['causes'].get((fell_off, OverturnAlarm.OVERTURNED)), OverturnAlarm.CAUSE_FELL_OFF_SUPPORT)
            self.assertEqual(last['causes'][(must_overturn, OverturnAlarm.OVERTURNED)], OverturnAlarm.CAUSE_ROCKING)
            level_cell = r'<tr data-item="%s" data-level="OVERTURNED">(?:(?!</tr>).)*<td data-cause="%s">(?:(?!</td>).)*</td>'
            off = re.search(level_cell % (re.escape(fell_off), 'fell_off_support'), dom)
            self.assertIsNotNone(off, 'no OVERTURNED row of %s with its cause in the alarm log' % fell_off)
            self.assertIn('fell off its support', off.group(0))
            self.assertRegex(dom, level_cell % (re.escape(must_overturn), 'rocking'))
            state = [s for s in last['states'].items if s.id == fell_off][0]
            self.assertEqual(state.contact, 'fell off its support')
            detail = chromium(['--window-size=1280,1000', '--dump-dom', url + '?poll=1&select=' + fell_off]).decode('utf-8', 'replace')
            margin = re.search(r'<td>support margin</td><td>(-?[0-9.]+) m to the edge</td>', detail)
            self.assertIsNotNone(margin, 'no support margin row in the detail of %s' % fell_off)
            self.assertAlmostEqual(float(margin.group(1)), state.support_margin, delta=1e-3)
            print('%s fell off its support: alarm and log say so, support margin %s m' % (fell_off, margin.group(1)))

        shot = rospy.get_param('~screenshot', '') or os.path.join(
            os.environ.get('ROS_HOME', os.path.expanduser('~/.ros')), 'dashboard_browser.png')
        os.makedirs(os.path.dirname(os.path.abspath(shot)), exist_ok=True)
        chromium(['--window-size=1400,1000', '--hide-scrollbars', '--screenshot=' + os.path.abspath(shot),
                  url + '?poll=1&select=' + must_overturn])
        self.assertGreater(os.path.getsize(shot), 10000)
        print('screenshot: %s' % shot)


if __name__ == '__main__':
    rospy.init_node('dashboard_browser')
    rostest.rosrun('rocking_monitor', 'dashboard_browser', DashboardBrowser)
