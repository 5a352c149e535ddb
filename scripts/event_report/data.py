"""event_report.data: loading what a report is made of: the bag (the monitor's topics and its input; a
redundant pair's alarms once each), the alarm journal's last event merged into the bag's alarms, the catalogue."""
import json
import os

from alarm_dedup import AlarmDedup  # scripts/alarm_dedup.py: rocking_report puts scripts/ on the path

from .common import CAUSE_CODES, JOURNAL_KINDS, LEVEL_CODES, ReportError


def read_bag(path, monitor=None, pair=None):
    """Everything the report needs from a bag, as plain Python data. pair: the other monitor of a redundant
    pair, whose alarms are merged with the monitor's (each alarm once, scripts/alarm_dedup.py)."""
    import rosbag
    if not os.path.exists(path):
        raise ReportError('%s: no such file' % path)
    try:
        bag = rosbag.Bag(path)
    except Exception as e:  # rosbag raises several types for a file that is not a bag
        raise ReportError('%s: not a readable bag (%s)' % (path, str(e).splitlines()[0] if str(e) else type(e).__name__))
    with bag:
        topics = bag.get_type_and_topic_info().topics
        def find(suffix, msgtype):
            found = [t for t, i in topics.items() if i.msg_type == msgtype and t.endswith('/' + suffix)
                     and (monitor is None or t == monitor.rstrip('/') + '/' + suffix)]
            return sorted(found)
        states_t = find('states', 'rocking_monitor/RockingStateArray')
        alarms_t = find('alarms', 'rocking_monitor/OverturnAlarm')
        if not states_t:
            have = ', '.join('%s (%s)' % (t, i.msg_type) for t, i in sorted(topics.items())) or 'nothing'
            raise ReportError('%s: no monitor topics: no %s/states of type rocking_monitor/RockingStateArray '
                              '(the bag holds %s); record the monitor too (README, "Post-event report")'
                              % (path, monitor or '<monitor>', have))
        if len(states_t) > 1:
            raise ReportError('%s: several monitors (%s): choose one with --monitor' % (path, ', '.join(states_t)))
        ns = states_t[0][:-len('/states')]
        pair = pair.rstrip('/') if pair else None
        if pair and (pair == ns or pair + '/alarms' not in topics):
            raise ReportError('%s: --pair %s: %s' % (path, pair, 'is the monitor itself' if pair == ns else
                              'the bag has no %s/alarms (record both monitors\' ~alarms)' % pair))
        sensors = sorted(t for t, i in topics.items() if i.msg_type in ('sensor_msgs/Imu', 'geometry_msgs/AccelStamped'))
        data = {'bag': path, 'monitor': ns, 'states': [], 'alarms': [], 'criteria': [], 'diagnostics': [],
                'sensors': {t: {'type': topics[t].msg_type, 't': [], 'a': []} for t in sensors},
                'catalogue': None}
        wanted = [ns + '/states', ns + '/alarms', ns + '/criteria', '/diagnostics', '/rocking_report/catalogue'] + sensors
        if pair:
            wanted.append(pair + '/alarms')
        dedup = AlarmDedup()  # in the order recorded: re-sent alarms (a restarted monitor) and the pair's, once
        for topic, m, _ in bag.read_messages(topics=wanted):
            if topic in data['sensors']:
                s = data['sensors'][topic]
                s['t'].append(m.header.stamp.to_sec())
                v = m.linear_acceleration if s['type'] == 'sensor_msgs/Imu' else m.accel.linear
                s['a'].append((v.x, v.y, v.z))
            elif topic == ns + '/states':
                data['states'].append(m)
            elif topic in (ns + '/alarms', (pair or ns) + '/alarms'):
                dedup.add(topic[:-len('/alarms')], m)
            elif topic == ns + '/criteria':
                data['criteria'].append(m)
            elif topic == '/diagnostics':
                data['diagnostics'].append(m)
            elif topic == '/rocking_report/catalogue':
                data['catalogue'] = json.loads(m.data)
    if not data['states']:
        raise ReportError('%s: %s/states has no messages' % (path, ns))
    data['pair'] = pair
    data['alarm_copies'] = {'merged': dedup.merged, 'repeats': dedup.repeats}
    # each alarm once; of two copies the earlier (its partner lagged), as the dashboard shows it
    data['alarms'] = dedup.alarms()
    if not alarms_t:
        data['no_alarm_topic'] = True  # the monitor's ~alarms was not recorded: say so in the report
    return data


def read_journal(path):
    """The journal's last event (what the monitor would re-send while it is open), with the warnings (a
    last line cut by a power cut) and errors (corrupt lines, skipped) as 'file:line: ...' texts."""
    if not os.path.exists(path):
        raise ReportError('%s: no such file' % path)
    with open(path, 'rb') as f:
        raw = f.read().decode('utf-8', errors='replace')
    lines = raw.split('\n')
    warnings, errors, records = [], [], []
    if lines and lines[-1] != '':
        warnings.append('%s:%d: last line cut in the middle (%d bytes without a newline: power cut while writing?); '
                        'read up to line %d' % (path, len(lines), len(lines[-1].encode()), len(lines) - 1))
    for n, line in enumerate(lines[:-1], 1):
        line = line.rstrip('\r')
        if not line.strip():
            continue
        try:
            r = json.loads(line)
            if not isinstance(r, dict):
                raise ValueError('not a JSON object')
            if r.get('kind') not in JOURNAL_KINDS:
                raise ValueError("unknown kind '%s'" % r.get('kind'))
            if r['kind'] != 'reset':
                for k in ('event', 'sequence', 'time', 'since_event_start'):
                    if k not in r:
                        raise ValueError("field '%s' missing" % k)
            if r['kind'] in ('alarm', 'probability_alarm') and r.get('level') not in LEVEL_CODES:
                raise ValueError("unknown level '%s'" % r.get('level'))
            records.append(r)
        except ValueError as e:  # json.JSONDecodeError is one
            errors.append('%s:%d: not a journal record (skipped): %s' % (path, n, e))
    last = next((r for r in reversed(records) if r['kind'] != 'reset'), None)
    event = last['event'] if last else None
    # Closed by a reset after it, or by its own end record (the monitor's end of the shaking: the report's
    # rule, ~event_quiet_time): either way the monitor would not re-send it.
    closed = last is not None and (records[-1]['kind'] == 'reset' or last['kind'] == 'end')
    return {'path': path, 'event': event, 'closed': closed, 'warnings': warnings, 'errors': errors,
            'records': [r for r in records if event is not None and r.get('event') == event]}


def merge_journal(data, journal):
    """Adds the journal's alarms that the bag lacks (same item and level) to data['alarms']."""
    import types
    have = {(a.item_id, a.level) for a in data['alarms']}
    data['journal'] = journal
    # Times on the bag's clock (seconds since its run's first sample) when the bag has alarms to tell it.
    t_first = next((a.event_time - a.time_since_first_sample for a in data['alarms']), None)
    for r in journal['records']:
        r['in_bag'] = r['kind'] != 'alarm' or (r['item'], LEVEL_CODES[r['level']]) in have
        if r['in_bag']:
            continue
        data['alarms'].append(types.SimpleNamespace(
            item_id=r['item'], description='', level=LEVEL_CODES[r['level']], plane=r.get('plane', ''),
            time_since_first_sample=r['since_event_start'] if t_first is None else r['time'] - t_first,
            event_time=r['time'],
            rotation_ratio=r.get('rotation_ratio', float('nan')), predicted_by=[], not_predicted_by=[],
            cause=CAUSE_CODES.get(r.get('cause', 'rocking'), 0)))


def load_catalogue(path):
    import yaml
    if not os.path.exists(path):
        raise ReportError('%s: no such file' % path)
    with open(path) as f:
        try:
            doc = yaml.safe_load(f)
        except yaml.YAMLError as e:
            raise ReportError('%s: not YAML (%s)' % (path, str(e).splitlines()[0]))
    if not isinstance(doc, dict) or not isinstance(doc.get('items'), list):
        raise ReportError('%s: no list "items" (a monitor catalogue, config/catalogue_example.yaml)' % path)
    return doc
