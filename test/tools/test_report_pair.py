#!/usr/bin/python3
"""rocking_report --pair (a redundant pair, docs/journal.md): the alarms read from a bag holding both
monitors' ~alarms are each shown once, the copy from every sample before one after a gap; a --pair the bag
does not hold is one clear error. argv[1] = scripts/rocking_report. Needs the generated messages
(ROCKING_PYTHON_PATH, as ctest sets it); no ROS master."""
import importlib.machinery
import importlib.util
import math
import os
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

BEYOND, OVERTURNED = 2, 4


def alarm(item, level, stamp, event_id, sequence, frozen_s):
    m = OverturnAlarm(item_id=item, level=level, event_id=event_id, sequence=sequence, frozen_s=frozen_s,
                      event_time=stamp, plane='x')
    m.header.stamp = rospy.Time.from_sec(stamp)
    return m


class ReportPair(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix='rocking_report_pair_')
        cls.bag = os.path.join(cls.dir, 'pair.bag')
        states = RockingStateArray(items=[RockingState(id='vase'), RockingState(id='rack')])
        states.header.stamp = rospy.Time.from_sec(99.0)
        t = rospy.Time.from_sec(1000.0)
        with rosbag.Bag(cls.bag, 'w') as bag:
            bag.write('/rocking_monitor_a/states', states, t)
            # a, respawned on a plain topic: its copy 0.1 s earlier after a 0.31 s gap, received first
            bag.write('/rocking_monitor_a/alarms', alarm('vase', BEYOND, 100.0, 'e/1', 4, 0.31), t + rospy.Duration(1))
            bag.write('/rocking_monitor_b/alarms', alarm('vase', BEYOND, 100.1, 'f/1', 5, 0.0), t + rospy.Duration(2))
            # a re-sends its journal's alarm (NaN) to a new subscriber: a repeat of the same (event, sequence)
            bag.write('/rocking_monitor_a/alarms', alarm('vase', BEYOND, 100.0, 'e/1', 4, math.nan), t + rospy.Duration(3))
            # only b raises this one
            bag.write('/rocking_monitor_b/alarms', alarm('rack', OVERTURNED, 101.0, 'f/1', 6, 0.0), t + rospy.Duration(4))

    def test_both_monitors_each_alarm_once_from_every_sample_first(self):
        data = report.read_bag(self.bag, '/rocking_monitor_a', '/rocking_monitor_b')
        self.assertEqual([(a.item_id, a.level, round(a.header.stamp.to_sec(), 6), a.frozen_s) for a in data['alarms']],
                         [('vase', BEYOND, 100.1, 0.0), ('rack', OVERTURNED, 101.0, 0.0)])
        self.assertEqual(data['alarm_copies'], {'merged': 1, 'repeats': 1})
        self.assertEqual(data['pair'], '/rocking_monitor_b')

    def test_without_pair_the_monitor_alone_each_alarm_once(self):
        data = report.read_bag(self.bag, '/rocking_monitor_a')
        self.assertEqual([(a.item_id, round(a.header.stamp.to_sec(), 6)) for a in data['alarms']], [('vase', 100.0)])
        self.assertEqual(data['alarm_copies'], {'merged': 0, 'repeats': 1})

    def test_a_pair_the_bag_lacks_or_the_monitor_itself_is_an_error(self):
        with self.assertRaisesRegex(report.ReportError, r'pair\.bag: --pair /rocking_monitor_c: the bag has no '
                                                        r'/rocking_monitor_c/alarms'):
            report.read_bag(self.bag, '/rocking_monitor_a', '/rocking_monitor_c')
        with self.assertRaisesRegex(report.ReportError, 'is the monitor itself'):
            report.read_bag(self.bag, '/rocking_monitor_a', '/rocking_monitor_a/')


if __name__ == '__main__':
    unittest.main()
