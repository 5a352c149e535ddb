#!/usr/bin/python3
"""rostest: the dashboard survives no catalogue, an empty catalogue and a monitor restarted on a
catalogue of another size (its snapshot follows each), and keeps serving throughout."""
import json
import os
import subprocess
import time
import unittest
import urllib.request

import roslib.packages
import rosgraph
import rosparam
import rospy
import rostest

NS = '/restart_mon'


def snapshot(url):
    with urllib.request.urlopen(url + 'api/snapshot', timeout=30) as r:
        return json.load(r)


def wait_for(what, predicate, timeout=30.0):
    deadline = time.time() + timeout
    while time.time() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.2)
    raise AssertionError('timed out waiting for ' + what)


def load(path, ns):
    for params, sub in rosparam.load_file(path, default_namespace=ns):
        rosparam.upload_params(sub, params)


class DashboardRestart(unittest.TestCase):
    def run_monitor_and_bag(self, what, ready):
        """The monitor on the bag; stopped once ready() (the dashboard shows what the bag did), so that
        nothing depends on how fast this machine is (issue 42). Returns ready()'s value."""
        log = open(os.path.join(os.environ.get('ROS_HOME', '/tmp'), 'dashboard_restart_monitor.log'), 'a')
        exe = [p for p in roslib.packages.find_node('rocking_monitor', 'monitor') if os.access(p, os.X_OK)][0]
        mon = subprocess.Popen([exe, '__name:=' + NS.strip('/')],
                               stdout=log, stderr=subprocess.STDOUT)
        try:
            # The bag once the monitor subscribed its input (registered; --wait-for-subscribers: connected).
            master = rosgraph.Master('/dashboard_restart')
            wait_for('the monitor to subscribe /ground/imu', lambda: any(
                t == '/ground/imu' and NS in nodes for t, nodes in master.getSystemState()[1]))
            subprocess.run(['rosbag', 'play', '-q', '--wait-for-subscribers', '-d', '1', '-u', '4', rospy.get_param('~bag')],
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=60)
            return wait_for(what, ready)
        finally:
            mon.send_signal(2)
            mon.wait(timeout=20)

    def test_survives_restarts(self):
        url = wait_for('~url', lambda: rospy.get_param('/dashboard/url', None))
        s = snapshot(url)
        self.assertEqual(s['items'], [])  # no catalogue yet: empty, not an error

        rospy.set_param(NS + '/items', [])
        time.sleep(1.5)  # the dashboard looks for a catalogue every second
        self.assertEqual(snapshot(url)['items'], [])

        load(rospy.get_param('~monitor_config'), NS)
        load(rospy.get_param('~catalogue'), NS)
        s = self.run_monitor_and_bag('6 items with states, museum_vase overturned', lambda: (
            lambda s: s if len(s['items']) == 6 and all('state' in i for i in s['items']) and
            any(i['id'] == 'museum_vase' and i['state']['mode'] == 'OVERTURNED' for i in s['items'])
            else None)(snapshot(url)))
        modes = {i['id']: i['state']['mode'] for i in s['items']}
        self.assertEqual(modes['museum_vase'], 'OVERTURNED')
        first_alarms = len(s['alarms'])
        self.assertGreater(first_alarms, 0)

        # Another catalogue, another size, other ids: the monitor restarted.
        cat3 = os.path.join(os.environ.get('ROS_HOME', '/tmp'), 'dashboard_restart_catalogue.yaml')
        subprocess.run(['/usr/bin/python3', os.path.join(os.path.dirname(os.path.abspath(__file__)),
                        '..', '..', 'scripts', 'make_catalogue.py'), '3', cat3], check=True,
                       stdout=subprocess.DEVNULL)
        rospy.delete_param(NS + '/items')
        load(cat3, NS)
        s = self.run_monitor_and_bag('the 3 new items with states', lambda: (lambda s: s if sorted(
            i['id'] for i in s['items'] if i.get('known') and 'state' in i) == ['item00000', 'item00001', 'item00002']
            else None)(snapshot(url)))
        ids = [i['id'] for i in s['items']]
        self.assertEqual(ids, ['item00000', 'item00001', 'item00002'])  # the old items gone with the old catalogue
        self.assertGreaterEqual(len(s['alarms']), first_alarms)  # the log keeps the first event
        with urllib.request.urlopen(url, timeout=30) as r:
            self.assertEqual(r.status, 200)


if __name__ == '__main__':
    rospy.init_node('dashboard_restart')
    rostest.rosrun('rocking_monitor', 'dashboard_restart', DashboardRestart)
