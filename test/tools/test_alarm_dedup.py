#!/usr/bin/python3
"""scripts/alarm_dedup.py (the redundant pair's rule, docs/journal.md): which copies are one alarm.
argv[1] = the scripts folder. Plain objects stand in for OverturnAlarm (no ROS needed)."""
import sys
import types
import unittest

sys.path.insert(0, sys.argv.pop(1))
from alarm_dedup import AlarmDedup  # noqa: E402

BEYOND, COMMITTED, OVERTURNED = 2, 3, 4


def alarm(item, level, stamp, event_id='2026-11-26T03:00:00.000Z/1', sequence=1, frozen_s=0.0):
    return types.SimpleNamespace(item_id=item, level=level, header=types.SimpleNamespace(stamp=stamp),
                                 event_id=event_id, sequence=sequence, frozen_s=frozen_s)


class Dedup(unittest.TestCase):
    def test_both_monitors_the_same_alarm_is_one_row(self):
        d = AlarmDedup()
        row, new = d.add('/a', alarm('vase', OVERTURNED, 100.25, sequence=3))
        self.assertTrue(new)
        row2, new2 = d.add('/b', alarm('vase', OVERTURNED, 100.25, sequence=3))
        self.assertIs(row2, row)
        self.assertFalse(new2)
        self.assertEqual(row.sources, {'/a', '/b'})
        self.assertEqual((len(d.rows()), d.merged, d.repeats), (1, 1, 0))

    def test_restarted_monitor_other_event_id_and_sequence_is_still_one_alarm(self):
        # b started later (its own sensor run: another id prefix) and journaled a gap (sequence shifted)
        d = AlarmDedup()
        d.add('/a', alarm('rack', COMMITTED, 101.0, '2026-11-26T03:00:00.000Z/1', 4))
        _, new = d.add('/b', alarm('rack', COMMITTED, 101.0, '2026-11-26T02:41:13.370Z/2', 6))
        self.assertFalse(new)
        self.assertEqual(len(d.rows()), 1)

    def test_resent_from_the_same_monitor_is_dropped_and_counted(self):
        d = AlarmDedup()
        d.add('/a', alarm('vase', BEYOND, 99.0, sequence=1))
        row, new = d.add('/a', alarm('vase', BEYOND, 99.0, sequence=1))
        self.assertEqual((row, new, d.repeats, len(d.rows())), (None, False, 1, 1))

    def test_the_copy_from_every_sample_is_shown_before_one_after_a_gap(self):
        # a respawned on a plain topic (0.31 s frozen): its copy 0.1 s earlier, first received, is replaced
        d = AlarmDedup()
        d.add('/a', alarm('vase', BEYOND, 102.671, sequence=4, frozen_s=0.31))
        row, new = d.add('/b', alarm('vase', BEYOND, 102.774, sequence=5, frozen_s=0.0))
        self.assertFalse(new)
        self.assertEqual((row.alarm.header.stamp, d.replaced), (102.774, 1))
        # the other order: the whole copy stays
        d2 = AlarmDedup()
        d2.add('/b', alarm('vase', BEYOND, 102.774, sequence=5))
        d2.add('/a', alarm('vase', BEYOND, 102.671, sequence=4, frozen_s=0.31))
        self.assertEqual(([a.header.stamp for a in d2.alarms()], d2.replaced), ([102.774], 0))
        # re-sent from a journal (NaN: not known) ranks after a whole copy too
        d3 = AlarmDedup()
        d3.add('/a', alarm('vase', BEYOND, 100.0, sequence=1, frozen_s=float('nan')))
        d3.add('/b', alarm('vase', BEYOND, 100.5, sequence=1))
        self.assertEqual([a.header.stamp for a in d3.alarms()], [100.5])

    def test_of_equal_copies_the_earlier_is_shown(self):
        d = AlarmDedup()
        d.add('/a', alarm('shelf', OVERTURNED, 109.3, sequence=9, frozen_s=0.4))  # a after a gap: 4.3 s late
        d.add('/b', alarm('shelf', OVERTURNED, 105.0, sequence=7, frozen_s=0.2))  # b after a gap of its own
        self.assertEqual([a.header.stamp for a in d.alarms()], [105.0])
        d2 = AlarmDedup()
        d2.add('/b', alarm('shelf', OVERTURNED, 105.0, sequence=7))
        d2.add('/a', alarm('shelf', OVERTURNED, 109.3, sequence=9))
        self.assertEqual([a.header.stamp for a in d2.alarms()], [105.0])

    def test_without_frozen_s_an_alarm_counts_as_whole(self):
        d = AlarmDedup()  # a bag recorded before the field existed
        old = types.SimpleNamespace(item_id='vase', level=BEYOND, header=types.SimpleNamespace(stamp=101.0),
                                    event_id='e/1', sequence=1)
        d.add('/a', alarm('vase', BEYOND, 100.0, frozen_s=0.5))
        d.add('/b', old)
        self.assertIs(d.alarms()[0], old)

    def test_one_monitor_never_merges_its_own_alarms(self):
        # after ~reset (a new event) the same level 2 s later from the same monitor is a new alarm
        d = AlarmDedup()
        d.add('/a', alarm('vase', BEYOND, 100.0, '2026-11-26T03:00:00.000Z/1', 1))
        _, new = d.add('/a', alarm('vase', BEYOND, 102.0, '2026-11-26T03:00:00.000Z/2', 1))
        self.assertTrue(new)
        # b's copies: one to each row, in order
        d.add('/b', alarm('vase', BEYOND, 100.0, '2026-11-26T03:00:00.000Z/1', 1))
        d.add('/b', alarm('vase', BEYOND, 102.0, '2026-11-26T03:00:00.000Z/2', 1))
        self.assertEqual([sorted(r.sources) for r in d.rows()], [['/a', '/b'], ['/a', '/b']])
        self.assertEqual([r.alarm.header.stamp for r in d.rows()], [100.0, 102.0])

    def test_beyond_the_window_or_another_level_or_item_is_another_alarm(self):
        d = AlarmDedup(window=10.0)
        d.add('/a', alarm('vase', BEYOND, 100.0))
        self.assertTrue(d.add('/b', alarm('vase', BEYOND, 110.5))[1])
        self.assertTrue(d.add('/b', alarm('vase', COMMITTED, 100.0, sequence=2))[1])
        self.assertTrue(d.add('/b', alarm('rack', BEYOND, 100.0, sequence=3))[1])
        self.assertFalse(d.add('/b', alarm('vase', BEYOND, 109.9, sequence=4))[1])  # a's row, within 10 s
        self.assertEqual(len(d.rows()), 4)

    def test_without_event_id_the_stamp_names_a_repeat(self):
        d = AlarmDedup()
        d.add('/a', alarm('vase', BEYOND, 100.0, '', 0))
        self.assertEqual(d.add('/a', alarm('vase', BEYOND, 100.0, '', 0)), (None, False))
        self.assertEqual(d.repeats, 1)

    def test_negative_window_is_refused(self):
        with self.assertRaisesRegex(ValueError, 'window must be >= 0 s, got -1'):
            AlarmDedup(window=-1.0)


if __name__ == '__main__':
    unittest.main()
