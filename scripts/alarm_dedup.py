"""One alarm, however many monitors raised it (issue 29 part 3, launch/monitor_pair.launch; docs/journal.md
"A redundant pair"). Shared by rocking_report, monitor_table.py and the pair's rostest; the dashboard has
the same rule in C++ (core::AlarmDedup, include/rocking_monitor/monitoring/alarm_dedup.hpp).

Why not (event_id, sequence): both are per journal. The event id's prefix is the first sample of each
monitor's own sensor run (two PCs started at different times differ), and the sequence counts every
record of that journal, so a restarted monitor's gap (a stale record) shifts all its later numbers.

The rule, on what both monitors take from the sensor alone (never their own clocks):
- from one monitor, an alarm received again (re-sent from its journal after a restart, a reconnect)
  has the same (event_id, sequence) and is dropped (without an event id: the same item, level, stamp);
- from another monitor, an alarm of the same item and level whose input stamp (header.stamp, the sample
  at which the level was reached) lies within WINDOW s of a shown alarm's, which that monitor has not
  already contributed to, is the same alarm: shown once. Of its copies the one shown is from a monitor
  whose items saw every sample (frozen_s 0: not respawned on a plain topic, no data gap), then the earliest.
Within one monitor an item alarms a level once per event, and a new event needs ~event_quiet_time (5 s)
of quiet first, so a monitor's own alarms are never merged with each other. A monitor that restarted on a
plain topic (a frozen gap) raises an alarm later or earlier than its partner (its items' motion differs
from the gap on: measured from 0.05 s earlier to 4.3 s later, docs/journal.md "Measured (pair)"): within
the window it is still the same alarm, shown at the partner's time; beyond it, shown twice, never lost.
"""

WINDOW = 10.0  # s of input stamps within which two monitors' alarms of the same item and level are one


class Row:
    """One alarm as shown: the best of its copies (`alarm`: see AlarmDedup) and the monitors that sent it."""
    __slots__ = ('alarm', 'sources', 'copies')

    def __init__(self, source, alarm):
        self.alarm = alarm
        self.sources = {source}
        self.copies = 1


def _rank(alarm):
    """0: the alarm comes from every sample (frozen_s 0; a bag recorded before the field: taken as 0);
    1: after a gap the items were frozen through, or not known (NaN: re-sent from a journal)."""
    return 0 if getattr(alarm, 'frozen_s', 0.0) == 0.0 else 1


def _stamp(alarm):
    s = alarm.header.stamp
    return s.to_sec() if hasattr(s, 'to_sec') else float(s)


class AlarmDedup:
    """add(source, alarm) -> (row, is_new); rows() in arrival order. `alarm` has the OverturnAlarm fields
    item_id, level, header.stamp, event_id, sequence, frozen_s (a message or anything with them; without
    frozen_s: taken as 0). A merged copy replaces the one shown when it is better: (frozen_s 0 first, then
    the earlier stamp); counted in `replaced`."""

    def __init__(self, window=WINDOW):
        if not window >= 0.0:
            raise ValueError('alarm dedup window must be >= 0 s, got %r' % (window,))
        self.window = window
        self._rows = []
        self._seen = set()  # (source, event_id, sequence) or (source, item, level, stamp)
        self._by_item_level = {}  # (item, level) -> rows
        self.repeats = 0  # received again from the same monitor: dropped, counted
        self.merged = 0   # the same alarm from another monitor: shown once, counted
        self.replaced = 0  # of those, copies shown instead of the one first received (better: see _rank)

    def add(self, source, alarm):
        if alarm.event_id:
            seen = (source, alarm.event_id, alarm.sequence)
        else:
            seen = (source, alarm.item_id, alarm.level, _stamp(alarm))
        if seen in self._seen:
            self.repeats += 1
            return None, False
        self._seen.add(seen)
        t = _stamp(alarm)
        rows = self._by_item_level.setdefault((alarm.item_id, alarm.level), [])
        for row in rows:
            if source not in row.sources and abs(_stamp(row.alarm) - t) <= self.window:
                row.sources.add(source)
                row.copies += 1
                self.merged += 1
                if (_rank(alarm), t) < (_rank(row.alarm), _stamp(row.alarm)):
                    row.alarm = alarm
                    self.replaced += 1
                return row, False
        row = Row(source, alarm)
        rows.append(row)
        self._rows.append(row)
        return row, True

    def rows(self):
        return list(self._rows)

    def alarms(self):
        return [r.alarm for r in self._rows]
