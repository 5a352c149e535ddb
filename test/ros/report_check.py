#!/usr/bin/python3
"""rostest: the post-event report of the pulse replay (test/ros/report.test).

Waits for the report the node writes when the event ends, parses its item table and checks it against
what this test received from the monitor itself: one row per catalogue item; for every alarm the
level's cell holds the alarm's time since the first sample (to 1e-6 s) and plane, and a level without an
alarm is empty; the item's outcome is its mode in the last ~states; the lead time is OVERTURNED minus
COMMITTED; the criteria cells are the OVERTURNED alarm's predicted_by / not_predicted_by. The pulse's
peaks are the closed form (PGA 4.0 m/s^2, PGV 4 * 0.6 / pi m/s). Then rocking_report run offline on
the node's bag must write the same table."""
import glob
import html.parser
import json
import os
import subprocess
import tempfile
import time
import unittest

import rospy
import rostest
from rocking_monitor.msg import OverturnAlarm, RockingStateArray

MODES = ['REST', 'ROCKING', 'BEYOND_TIPPING', 'COMMITTED', 'OVERTURNED']
LEVELS = {2: 'BEYOND_TIPPING', 3: 'COMMITTED', 4: 'OVERTURNED'}


class Table(html.parser.HTMLParser):
    """Rows of <table id="items"> and <table id="peaks"> as lists of attribute dicts (one per cell)."""

    def __init__(self):
        super().__init__()
        self.table, self.rows, self.peaks = None, {}, {}
        self.row = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == 'table':
            self.table = a.get('id')
        elif tag == 'tr' and self.table == 'items' and 'data-item' in a:
            self.row = self.rows.setdefault(a['data-item'], {'outcome': a.get('data-outcome'), 'cells': []})
        elif tag == 'tr' and self.table == 'peaks' and 'data-component' in a:
            self.row = self.peaks.setdefault(a['data-component'], {'cells': []})
        elif tag == 'tr':
            self.row = None
        elif tag == 'td' and self.row is not None:
            self.row['cells'].append(a)

    def handle_endtag(self, tag):
        if tag == 'table':
            self.table, self.row = None, None


def parse(path):
    t = Table()
    with open(path, encoding='utf-8') as f:
        t.feed(f.read())
    return t


class JournalRows(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.rows = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == 'tr' and 'data-sequence' in a:
            self.rows.append(a)


def journal_rows(path):
    """The rows of the report's <table id="journal">, as attribute dicts."""
    t = JournalRows()
    with open(path, encoding='utf-8') as f:
        t.feed(f.read())
    return t.rows


def summary(table):
    """{item: {'outcome', 'x', 'y', level: (time, plane) or None, 'lead', 'predicted', 'not_predicted'}}"""
    out = {}
    for item, row in table.rows.items():
        d = {'outcome': row['outcome']}
        for c in row['cells']:
            if 'data-level' in c:
                d[c['data-level']] = (float(c['data-time']), c['data-plane']) if 'data-time' in c else None
            for k in ('data-outcome-x', 'data-outcome-y', 'data-lead', 'data-predicted', 'data-not-predicted'):
                if k in c:
                    d[k[5:]] = c[k]
        out[item] = d
    return out


class Report(unittest.TestCase):
    def test_report_table_equals_the_monitors_alarms(self):
        report_dir = rospy.get_param('~report_dir')
        must_overturn, must_survive = rospy.get_param('~must_overturn'), rospy.get_param('~must_survive')
        start = time.time()
        for old in glob.glob(os.path.join(report_dir, 'event_*')):  # earlier runs of this test
            if os.path.getmtime(old) < start - 1.0:
                os.remove(old)
        got = {'states': None, 'alarms': []}
        rospy.Subscriber('/rocking_monitor/states', RockingStateArray, lambda m: got.update(states=m), queue_size=10)
        rospy.Subscriber('/rocking_monitor/alarms', OverturnAlarm, lambda m: got['alarms'].append(m), queue_size=1000)
        deadline = time.time() + 120
        pages = []
        while not pages:
            self.assertLess(time.time(), deadline, 'no report in %s' % report_dir)
            time.sleep(0.2)
            pages = [p for p in glob.glob(os.path.join(report_dir, 'event_*.html')) if os.path.getmtime(p) >= start - 1.0]
        self.assertEqual(len(pages), 1, pages)
        page = pages[0]
        bag = page[:-len('.html')] + '.bag'
        self.assertTrue(os.path.exists(bag))
        print('report: %s' % page)

        with open(page, encoding='utf-8') as f:  # ended by the monitor's states, not by the input stopping
            self.assertIn('every item at rest or overturned for 2.0 s', f.read())
        table = parse(page)
        rows = summary(table)
        ids = [s.id for s in got['states'].items]
        self.assertEqual(sorted(rows), sorted(ids))
        alarms = {(a.item_id, LEVELS[a.level]): a for a in got['alarms']}
        self.assertIn((must_overturn, 'OVERTURNED'), alarms)
        self.assertNotIn((must_survive, 'OVERTURNED'), alarms)
        for s in got['states'].items:
            r = rows[s.id]
            self.assertEqual(r['outcome'], MODES[s.mode], s.id)
            self.assertEqual(r['outcome-x'], MODES[s.x.mode], s.id)
            self.assertEqual(r['outcome-y'], MODES[s.y.mode] if s.plane_count == 2 else '', s.id)
            for level in LEVELS.values():
                a = alarms.get((s.id, level))
                if a is None:
                    self.assertIsNone(r[level], '%s %s: in the report, not on ROS' % (s.id, level))
                else:
                    self.assertIsNotNone(r[level], '%s %s: on ROS, not in the report' % (s.id, level))
                    self.assertAlmostEqual(r[level][0], a.time_since_first_sample, delta=1e-6)
                    self.assertEqual(r[level][1], a.plane)
            c, o = alarms.get((s.id, 'COMMITTED')), alarms.get((s.id, 'OVERTURNED'))
            if c and o:
                self.assertAlmostEqual(float(r['lead']), o.time_since_first_sample - c.time_since_first_sample, delta=2e-6)
            else:
                self.assertEqual(r['lead'], '')
            top = next((alarms[(s.id, l)] for l in ('OVERTURNED', 'COMMITTED', 'BEYOND_TIPPING') if (s.id, l) in alarms), None)
            self.assertEqual(r['predicted'], ','.join(top.predicted_by) if top else '')
            self.assertEqual(r['not-predicted'], ','.join(top.not_predicted_by) if top else '')
        print('items: %s' % rows)

        # The pulse a = 4.0 sin(2 pi t / 0.6) m/s^2 on x for 0.6 s: PGA 4.0 (a sample at its crest),
        # PGV 4 * 0.6 / pi = 0.7639 m/s (trapezoidal integration at 200 Hz: within 0.1 %); y and z at rest.
        pga = {k: float(v['cells'][1]['data-pga']) for k, v in table.peaks.items()}
        pgv = {k: float(v['cells'][3]['data-pgv']) for k, v in table.peaks.items()}
        self.assertAlmostEqual(pga['x'], 4.0, delta=1e-6)
        self.assertAlmostEqual(pgv['x'], 4.0 * 0.6 / 3.141592653589793, delta=1e-3)
        self.assertLess(max(pga['y'], pga['z']), 1e-6)

        # Offline, from the node's bag: the same table (live == offline).
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, 'offline.html')
            tool = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'scripts', 'rocking_report')
            subprocess.run(['/usr/bin/python3', tool, bag, '-o', out], check=True, timeout=120)
            self.assertEqual(summary(parse(out)), rows)
            # A valid bag with a catalogue that is not there: one error line, exit status 2, no report.
            bad = subprocess.run(['/usr/bin/python3', tool, bag, '-o', out + '2', '--catalogue', os.path.join(tmp, 'none.yaml')],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120)
            self.assertEqual(bad.returncode, 2)
            self.assertEqual(bad.stderr.decode().splitlines(), ['rocking_report: error: %s: no such file' % os.path.join(tmp, 'none.yaml')])
            self.assertFalse(os.path.exists(out + '2'))

        # The alarm journal (issue 19): the live report lists the monitor's journal, one row per alarm
        # received here, each also in the bag.
        journal = os.path.join(os.environ.get('ROS_HOME') or os.path.expanduser('~/.ros'), 'rocking_monitor',
                               'journal.jsonl')
        live_rows = journal_rows(page)
        # The pulse's shaking stops within the bag: the monitor ends the event (issue 29), its last row.
        self.assertEqual(live_rows[-1]['data-kind'], 'end')
        with open(page, encoding='utf-8') as f:
            self.assertIn('closed: the shaking stopped', f.read())
        live_rows = [r for r in live_rows if r['data-kind'] == 'alarm']
        self.assertEqual([(r['data-item'], r['data-level'], int(r['data-sequence']), r['data-in-bag']) for r in live_rows],
                         [(a.item_id, LEVELS[a.level], a.sequence, 'yes') for a in sorted(got['alarms'], key=lambda a: a.sequence)])
        # Offline with a journal holding one alarm the bag lacks (must_survive OVERTURNED 1.5 s after the
        # first sample) and a last line cut by a power cut: the alarm is in the items table, the cut named.
        with open(journal) as f:
            lines = f.read().splitlines()
        records = [json.loads(l) for l in lines]
        last = [r for r in records if r['kind'] == 'alarm'][-1]
        first_alarm = got['alarms'][0]
        t_first = first_alarm.event_time - first_alarm.time_since_first_sample
        extra = dict(last, item=must_survive, level='OVERTURNED', plane='x',
                     sequence=max(r.get('sequence', 0) for r in records) + 1, time=t_first + 1.5, since_event_start=1.5)
        # Into the event, before its end record (issue 29) when it has one.
        body = lines[:-1] + [json.dumps(extra), lines[-1]] if records[-1]['kind'] == 'end' else lines + [json.dumps(extra)]
        with tempfile.TemporaryDirectory() as tmp:
            j = os.path.join(tmp, 'journal.jsonl')
            with open(j, 'w') as f:
                f.write('\n'.join(body) + '\n' + lines[0][:20])
            out = os.path.join(tmp, 'with_journal.html')
            tool = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'scripts', 'rocking_report')
            run = subprocess.run(['/usr/bin/python3', tool, bag, '-o', out, '--journal', j],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120)
            self.assertEqual(run.returncode, 0, run.stderr.decode())
            self.assertIn('%s:%d: last line cut in the middle' % (j, len(lines) + 2), run.stderr.decode())
            merged = summary(parse(out))
            self.assertAlmostEqual(merged[must_survive]['OVERTURNED'][0], 1.5, delta=1e-6)
            self.assertEqual(merged[must_survive]['OVERTURNED'][1], 'x')
            rows_j = [r for r in journal_rows(out) if r['data-kind'] == 'alarm']
            self.assertEqual(len(rows_j), len(got['alarms']) + 1)
            self.assertEqual((rows_j[-1]['data-item'], rows_j[-1]['data-in-bag']), (must_survive, 'no'))


if __name__ == '__main__':
    rospy.init_node('report_check')
    rostest.rosrun('rocking_monitor', 'report_check', Report)
