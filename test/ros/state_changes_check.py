#!/usr/bin/python3
"""rostest: ~state_changes carries every change (test/ros/monitor_state_changes.test).

A subscriber of a large catalogue takes one full ~states, then applies ~state_changes by id. Over the
pulse replay (items rest, rock, slide and overturn) the picture built that way from the first full
~states must equal, field by field, the last full ~states once the replay is over; the changes must be
a diff (after the first message, fewer items than the catalogue; the quiet end sends none) and must
have carried motion (some item not at rest)."""
import time
import unittest

import rospy
import rostest
from rocking_monitor.msg import RockingStateArray

PLANE_FIELDS = ['mode', 'pivot', 'theta', 'theta_dot', 'rotation_ratio', 'energy_margin', 'impacts', 'violations',
                'contact_mode', 'slip', 'model']
ITEM_FIELDS = ['mode', 'plane_count', 'plane', 'pivot', 'theta', 'theta_dot', 'rotation_ratio', 'energy_margin',
               'impacts', 'violations', 'model_valid', 'contact_mode', 'slip', 'model', 'tilt', 'contact']


def state_of(s):
    """Every state field of one RockingState (not input_stamp and stale, which are per sample)."""
    out = {f: getattr(s, f) for f in ITEM_FIELDS}
    for p in ('x', 'y'):
        out.update({p + '.' + f: getattr(getattr(s, p), f) for f in PLANE_FIELDS})
    return out


class StateChanges(unittest.TestCase):
    def test_changes_applied_to_one_states_give_the_last_states(self):
        got = {'states': [], 'changes': [], 'time': time.time()}

        def on(kind):
            def f(m):
                got[kind].append(m)
                got['time'] = time.time()
            return f
        monitor = rospy.get_param('~monitor')
        rospy.Subscriber(monitor + '/states', RockingStateArray, on('states'), queue_size=1000)
        rospy.Subscriber(monitor + '/state_changes', RockingStateArray, on('changes'), queue_size=1000)
        deadline = time.time() + 100
        # The replay is over when nothing arrived for 3 s after the states showed motion.
        while not (got['states'] and any(s.mode != 0 for m in got['states'] for s in m.items) and
                   time.time() - got['time'] > 3.0):
            self.assertLess(time.time(), deadline, 'the replay did not end with motion on ~states')
            time.sleep(0.1)
        first, last = got['states'][0], got['states'][-1]
        picture = {s.id: state_of(s) for s in first.items}
        applied = 0
        for m in got['changes']:
            if m.header.stamp < first.header.stamp:
                continue  # older than the full picture taken
            for s in m.items:
                self.assertIn(s.id, picture)
                picture[s.id] = state_of(s)
                applied += 1
        self.assertGreater(applied, 0)
        for s in last.items:
            self.assertEqual(picture[s.id], state_of(s), 'item %s' % s.id)
        n = len(last.items)
        self.assertTrue(any(0 < len(m.items) < n for m in got['changes'][1:]), 'no change message is a diff')
        self.assertEqual(len(got['changes'][-1].items), 0, 'the quiet end still sends changes')
        self.assertTrue(any(s.mode != 0 for m in got['changes'] for s in m.items), 'no motion in the changes')


if __name__ == '__main__':
    rospy.init_node('state_changes_check')
    rostest.rosrun('rocking_monitor', 'state_changes_check', StateChanges)
