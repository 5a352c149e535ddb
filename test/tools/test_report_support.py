#!/usr/bin/python3
"""rocking_report and an item on a support (issue 51): an item that slid off its plinth is OVERTURNED with
the cause "fell off its support" in the banner, the items table and the journal table (also for an alarm
read from the journal only); the line under its name gives the live support margin the monitor published
(least and last, m); an item that overturned by rocking says nothing of a support. argv[1] =
scripts/rocking_report. Needs the generated messages (ROCKING_PYTHON_PATH, as ctest sets it); no ROS master."""
import importlib.machinery
import importlib.util
import json
import math
import os
import re
import shutil
import sys
import tempfile
import unittest

TOOL = sys.argv.pop(1)
sys.path.insert(0, os.environ.get('ROCKING_PYTHON_PATH', ''))
import rosbag  # noqa: E402
import rospy  # noqa: E402
from rocking_monitor.msg import OverturnAlarm, RockingState, RockingStateArray  # noqa: E402

loader = importlib.machinery.SourceFileLoader('rocking_report', TOOL)
spec = importlib.util.spec_from_loader('rocking_report', loader)
report = importlib.util.module_from_spec(spec)
loader.exec_module(report)

OVERTURNED, REST = 4, 0
T0 = 1000.0  # the first sample, s since 1970
# the bust's published support margins, m: it slides towards the edge, reaches it and falls off
BUST_MARGINS = [0.4, 0.25, 0.1, 0.0]


def state(item, mode, margin, contact, t):
    s = RockingState(id=item, mode=mode, plane='x', plane_count=2, model='rocking_3d', contact=contact,
                     support_margin=margin)
    s.input_stamp = rospy.Time.from_sec(t)
    return s


def alarm(item, cause, t, sequence):
    m = OverturnAlarm(item_id=item, level=OVERTURNED, cause=cause, plane='3d', event_id='e/1', sequence=sequence,
                      event_time=t, time_since_first_sample=t - T0, frozen_s=0.0)
    m.header.stamp = rospy.Time.from_sec(t)
    return m


def journal_line(item, sequence, t, cause=None):
    r = {'kind': 'alarm', 'event': 'e/1', 'sequence': sequence, 'item': item, 'level': 'OVERTURNED', 'plane': '3d',
         'time': t, 'event_start': T0, 'since_event_start': t - T0, 'written': t}
    if cause:
        r['cause'] = cause
    return json.dumps(r) + '\n'


class ReportSupport(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix='rocking_report_support_')
        bag_path = os.path.join(cls.dir, 'plinth.bag')
        with rosbag.Bag(bag_path, 'w') as bag:
            for k, margin in enumerate(BUST_MARGINS):
                t = T0 + k
                last = k == len(BUST_MARGINS) - 1
                msg = RockingStateArray(items=[
                    state('bust', OVERTURNED if last else REST, margin, 'fell off its support' if last else 'sliding', t),
                    state('vase', OVERTURNED if last else REST, math.nan, 'edge 2' if last else '', t),
                    state('urn', OVERTURNED if last else REST, 0.05, '', t)])
                msg.header.stamp = rospy.Time.from_sec(t)
                bag.write('/rocking_monitor/states', msg, rospy.Time.from_sec(t))
            bag.write('/rocking_monitor/alarms', alarm('bust', OverturnAlarm.CAUSE_FELL_OFF_SUPPORT, T0 + 2.5, 1),
                      rospy.Time.from_sec(T0 + 3))
            bag.write('/rocking_monitor/alarms', alarm('vase', OverturnAlarm.CAUSE_ROCKING, T0 + 2.75, 2),
                      rospy.Time.from_sec(T0 + 3))
        journal = os.path.join(cls.dir, 'journal.jsonl')
        with open(journal, 'w') as f:
            f.write(journal_line('bust', 1, T0 + 2.5, 'fell_off_support'))
            f.write(journal_line('vase', 2, T0 + 2.75))
            f.write(journal_line('urn', 3, T0 + 2.875, 'fell_off_support'))  # the bag lost this one
        out = os.path.join(cls.dir, 'report.html')
        report.write_report(bag_path, out, journal=journal)
        with open(out, encoding='utf-8') as f:
            cls.page = f.read()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def row(self, table_id, item):
        table = re.search(r'<table id="%s">(.*?)</table>' % table_id, self.page, re.S)
        self.assertIsNotNone(table, 'no table %s' % table_id)
        found = re.search(r'<tr data-(?:sequence="\d+" data-kind="alarm" data-)?item="%s"[^>]*>.*?</tr>' % item,
                          table.group(1), re.S)
        self.assertIsNotNone(found, 'no row of %s in %s' % (item, table_id))
        return found.group(0)

    def test_the_banner_names_the_items_that_fell_off_their_support(self):
        banner = re.search(r'<div class="banner" id="banner">([^<]*)</div>', self.page).group(1)
        self.assertEqual(banner, 'Overturned: bust (fell off its support), vase, urn (fell off its support)')

    def test_the_overturned_time_says_why(self):
        bust = self.row('items', 'bust')
        self.assertRegex(bust, r'data-level="OVERTURNED" data-time="2\.500000" data-plane="3d" '
                               r'data-cause="fell_off_support"[^>]*>[^<]*<br>fell off its support</td>')
        vase = self.row('items', 'vase')
        self.assertRegex(vase, r'data-level="OVERTURNED" data-time="2\.750000" data-plane="3d" data-cause="rocking"')
        self.assertNotIn('fell off', vase)
        urn = self.row('items', 'urn')  # from the journal only
        self.assertIn('data-cause="fell_off_support"', urn)

    def test_the_support_margin_is_the_least_and_last_published(self):
        bust = self.row('items', 'bust')
        self.assertIn('data-support-min="%.6f" data-support-final="%.6f"' % (min(BUST_MARGINS), BUST_MARGINS[-1]), bust)
        self.assertIn('least 0.000 m, at the end 0.000 m', bust)
        self.assertIn('data-support-min="0.050000" data-support-final="0.050000"', self.row('items', 'urn'))
        self.assertNotIn('support margin', self.row('items', 'vase'))  # NaN: no support

    def test_the_journal_table_says_the_cause(self):
        self.assertIn('data-cause="fell_off_support"', self.row('journal', 'bust'))
        self.assertIn('<td>OVERTURNED, fell off its support</td>', self.row('journal', 'bust'))
        self.assertIn('data-cause="rocking"', self.row('journal', 'vase'))
        self.assertIn('<td>OVERTURNED</td>', self.row('journal', 'vase'))


if __name__ == '__main__':
    unittest.main()
