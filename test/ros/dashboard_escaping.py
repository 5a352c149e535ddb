#!/usr/bin/python3
"""rostest (issue 52 item 6): hostile text on the dashboard page stays text.

The catalogue's description (test/ros/dashboard_escaping.test) and an alarm's item id, description,
plane and criteria, and a state's plane and model, carry a <script> and an <img src=x onerror=...>,
each of which would mark <body data-pwned=...> if the page ran it. The page (headless Chromium,
--dump-dom) must hold no such element and no mark, and show the text itself, escaped, in the item
detail and the alarm log."""
import json
import re
import shutil
import subprocess
import tempfile
import time
import unittest
import urllib.request

import rospy
import rostest
from rocking_monitor.msg import OverturnAlarm, RockingState, RockingStateArray

FLAGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
         '--disable-background-networking', '--disable-component-update', '--disable-sync',
         '--virtual-time-budget=5000']


def hostile(where):
    return ('%s<script>document.body.setAttribute("data-pwned", "%s script")</script>'
            '<img src=x onerror="document.body.setAttribute(\'data-pwned\', \'%s img\')">' % (where, where, where))


def chromium(args, timeout=90):
    with tempfile.TemporaryDirectory() as profile:
        return subprocess.run(['chromium'] + FLAGS + ['--user-data-dir=' + profile] + args,
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, timeout=timeout, check=True).stdout


def wait_for(condition, what, timeout=60):
    deadline = time.time() + timeout  # a hang, not a verdict
    while not condition():
        if time.time() > deadline:
            raise AssertionError('gave up waiting for ' + what)
        time.sleep(0.1)


class DashboardEscaping(unittest.TestCase):
    def test_hostile_text_is_shown_as_text_and_never_run(self):
        self.assertIsNotNone(shutil.which('chromium'), 'chromium not installed (scripts/install_deps.sh)')
        states = rospy.Publisher('/rocking_monitor/states', RockingStateArray, queue_size=1, latch=True)
        alarms = rospy.Publisher('/rocking_monitor/alarms', OverturnAlarm, queue_size=10, latch=True)
        wait_for(lambda: rospy.has_param('/dashboard/url'), '/dashboard/url')
        url = rospy.get_param('/dashboard/url')
        wait_for(lambda: states.get_num_connections() > 0 and alarms.get_num_connections() > 0, 'the dashboard to subscribe')

        s = RockingState(id='vase_1', mode=RockingState.COMMITTED, plane=hostile('plane'), plane_count=1,
                         model=hostile('model'), rotation_ratio=1.5, energy_margin=-0.1, model_valid=True)
        msg = RockingStateArray(items=[s])
        msg.header.stamp = rospy.Time.now()
        states.publish(msg)
        a = OverturnAlarm(item_id=hostile('item'), description=hostile('alarm description'),
                          level=OverturnAlarm.COMMITTED, plane=hostile('alarm plane'),
                          predicted_by=[hostile('criterion')], event_id='2026-11-29T08:00:00.000Z/1', sequence=1,
                          event_time=100.0, time_since_first_sample=1.0, rotation_ratio=1.5)
        a.header.stamp = rospy.Time(100)
        alarms.publish(a)

        def snapshot():
            with urllib.request.urlopen(url + 'api/snapshot', timeout=10) as r:
                return json.load(r)
        wait_for(lambda: snapshot().get('alarms') and any(i.get('state') for i in snapshot()['items']),
                 'the alarm and the state in /api/snapshot')

        dom = chromium(['--window-size=1280,1000', '--dump-dom', url + '?poll=1&select=vase_1']).decode('utf-8', 'replace')
        self.assertIn('<tr data-item="vase_1"', dom, 'the page did not render the item table')
        body = re.search(r'<body[^>]*>', dom)
        self.assertIsNotNone(body, 'no <body> in the DOM')
        self.assertNotIn('data-pwned', body.group(0), 'the page ran injected text')
        self.assertIsNone(re.search(r'<img[^>]*src="?x', dom), 'an injected <img> became an element')
        # The page's own scripts only: none of them is the injected one (its text would be inside).
        scripts = re.findall(r'<script[^>]*>(?:(?!</script>).)*</script>', dom, re.S)
        self.assertTrue(all('data-pwned' not in t for t in scripts), scripts)
        # Shown as text, escaped in the serialised DOM: the item's description in its detail, and the
        # alarm's item id, plane and criteria in the alarm log; the state's plane and model in the detail.
        for where in ('description', 'item', 'alarm plane', 'criterion', 'plane', 'model'):
            self.assertIn('%s&lt;script&gt;document.body.setAttribute("data-pwned", "%s script")&lt;/script&gt;' % (where, where),
                          dom, 'the %s text is not shown as text' % where)
        print('hostile text in 6 places shown as text; %d script elements on the page (its own)' % len(scripts))


if __name__ == '__main__':
    rospy.init_node('dashboard_escaping')
    rostest.rosrun('rocking_monitor', 'dashboard_escaping', DashboardEscaping)
