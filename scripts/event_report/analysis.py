"""event_report.analysis: the numbers of the report: the ground motion and its response spectrum, the items'
Housner periods, each item's outcome, alarms and lead time, and the monitor's health from /diagnostics."""
import collections
import math

from .common import CAUSES, DAMPING, G, LEVELS, MODES, QUIET_THRESHOLD


def nigam_jennings(acc, dt, periods, zeta=DAMPING):
    """Peak relative displacement of 5 %-damped oscillators under a ground acceleration linear between
    samples: the exact Nigam & Jennings (1969) recursion, vectorised over the periods."""
    import numpy as np
    w = 2.0 * np.pi / np.asarray(periods, float)
    wd = w * math.sqrt(1.0 - zeta * zeta)
    e, s, c = np.exp(-zeta * w * dt), np.sin(wd * dt), np.cos(wd * dt)
    q = zeta / math.sqrt(1.0 - zeta * zeta)
    a11, a12 = e * (q * s + c), e * s / wd
    a21, a22 = -w / math.sqrt(1.0 - zeta * zeta) * e * s, e * (c - q * s)
    k1 = (2.0 * zeta * zeta - 1.0) / (w * w * dt)
    k2 = 2.0 * zeta / (w ** 3 * dt)
    b11 = e * ((k1 + zeta / w) * s / wd + (k2 + 1.0 / w ** 2) * c) - k2
    b12 = -e * (k1 * s / wd + k2 * c) - 1.0 / w ** 2 + k2
    b21 = e * ((k1 + zeta / w) * (c - q * s) - (k2 + 1.0 / w ** 2) * (wd * s + zeta * w * c)) + 1.0 / (w * w * dt)
    b22 = -e * (k1 * (c - q * s) - k2 * (wd * s + zeta * w * c)) - 1.0 / (w * w * dt)
    x = np.zeros_like(w)
    v = np.zeros_like(w)
    peak = np.zeros_like(w)
    for i in range(len(acc) - 1):
        x, v = a11 * x + a12 * v + b11 * acc[i] + b12 * acc[i + 1], a21 * x + a22 * v + b21 * acc[i] + b22 * acc[i + 1]
        np.maximum(peak, np.abs(x), out=peak)
    return peak


def ground_motion(sensor):
    """Ground acceleration (m/s^2, sensor axes) with the at-rest reading removed, velocity, peaks."""
    import numpy as np
    t = np.asarray(sensor['t'], float)
    a = np.asarray(sensor['a'], float)
    order = np.argsort(t, kind='stable')
    t, a = t[order], a[order]
    if sensor['type'] == 'sensor_msgs/Imu':  # REP 145 specific force, gravity included
        # The at-rest reading is the first sample's, as the monitor's baseline starts (README: start the
        # monitor with the building at rest); a mean over a window would take in a shock that starts at once.
        a = a - a[0]
    dts = np.diff(t)
    dt = float(np.median(dts)) if len(dts) else 0.0
    v = np.zeros_like(a)
    if len(t) > 1:
        v[1:] = np.cumsum(0.5 * (a[1:] + a[:-1]) * dts[:, None], axis=0)
    shaking = np.nonzero(np.maximum(np.hypot(a[:, 0], a[:, 1]), np.abs(a[:, 2])) >= QUIET_THRESHOLD)[0]
    gm = {'t': t, 'a': a, 'v': v, 'dt': dt,
          'pga': np.abs(a).max(axis=0) if len(a) else np.zeros(3),
          'pgv': np.abs(v).max(axis=0) if len(v) else np.zeros(3),
          'start': float(t[shaking[0]]) if len(shaking) else None,
          'end': float(t[shaking[-1]]) if len(shaking) else None,
          'gaps': int(np.sum(dts > 1.5 * dt)) if dt > 0 else 0,
          'longest_gap': float(dts.max()) if len(dts) else 0.0,
          'non_increasing': int(np.sum(dts <= 0.0))}
    return gm


def nominal(value):
    """A catalogue number or the nominal value of a probability law (README, "Uncertain parameters")."""
    if isinstance(value, dict):
        if 'nominal' in value:
            return float(value['nominal'])
        if 'uniform' in value:
            return 0.5 * (value['uniform'][0] + value['uniform'][1])
        if 'normal' in value:
            return float(value['normal'][0])
        if 'lognormal' in value:
            return value['lognormal'][0] * math.exp(0.5 * value['lognormal'][1] ** 2)
        raise ValueError('unknown law %s' % sorted(value))
    return float(value)


def housner_period(width, cg_height, nu1, radius_of_gyration):
    """T = 2 pi / p of the pivot with the smaller tipping angle (core physics/criteria.cpp):
    p^2 = g R / (i_g^2 + R^2), R = hypot(nu B, h)."""
    nu = min(nu1, 1.0 - nu1)
    r = math.hypot(nu * width, cg_height)
    p = math.sqrt(G * r / (radius_of_gyration ** 2 + r * r))
    return 2.0 * math.pi / p


def item_periods(entry):
    """{'x': T, 'y': T} for one catalogue entry, with the catalogue's defaults (ros/catalogue.cpp)."""
    b, h = nominal(entry['width']), nominal(entry['cg_height'])
    nu = nominal(entry.get('eccentricity', 0.5))
    cylinder = entry.get('shape', 'box') == 'cylinder'
    if 'radius_of_gyration' in entry:
        ig = nominal(entry['radius_of_gyration'])
    elif cylinder:
        ig = math.sqrt(b * b / 16.0 + h * h / 3.0)
    else:
        ig = None
    out = {'x': housner_period(b, h, nu, ig if ig is not None else math.sqrt((b * b + 4 * h * h) / 12.0))}
    if 'depth' in entry:
        d = nominal(entry['depth'])
        if 'radius_of_gyration_y' in entry:
            iy = nominal(entry['radius_of_gyration_y'])
        elif cylinder:
            iy = math.sqrt(d * d / 16.0 + h * h / 3.0)
        elif ig is not None:  # mass spread uniformly in plan (core y_plane_body)
            iy = math.sqrt(ig * ig + (d * d - b * b) / 12.0)
        else:
            iy = math.sqrt((d * d + 4 * h * h) / 12.0)
        out['y'] = housner_period(d, h, nominal(entry.get('eccentricity_y', 0.5)), iy)
    return out


def summarise_items(data):
    """Per item: outcome per plane, max theta/alpha per plane, alarms, criteria, series for the figures."""
    first = data['states'][0]
    items = collections.OrderedDict()
    for s in first.items:
        items[s.id] = {'id': s.id, 'planes': 2 if s.plane_count == 2 else 1, 'max': {'x': 0.0, 'y': 0.0},
                       'final': {}, 'alarms': {}, 'criteria': collections.OrderedDict(), 'description': '',
                       'series': {'t': [], 'x': [], 'y': [], 'solid': []}, 'left_rest': False, 'p_overturned': None,
                       'solid': None}
    for msg in data['states']:
        t = msg.header.stamp.to_sec()
        for s in msg.items:
            it = items.get(s.id)
            if it is None or s.input_stamp.is_zero():  # another catalogue after a restart; no sample yet
                continue
            it['planes'] = 2 if s.plane_count == 2 else 1
            for name in ('x', 'y'):
                p = getattr(s, name)
                it['max'][name] = max(it['max'][name], p.rotation_ratio)
            it['final'] = {'x': MODES[s.x.mode], 'y': MODES[s.y.mode] if s.plane_count == 2 else None,
                           'item': MODES[s.mode]}
            if s.ensemble_size > 0:
                it['p_overturned'] = (s.p_overturned.probability, s.p_overturned.lower, s.p_overturned.upper,
                                      s.ensemble_size)
            if s.mode != 0:
                it['left_rest'] = True
            it['series']['t'].append(s.input_stamp.to_sec())
            it['series']['x'].append(s.x.rotation_ratio * (1 if s.x.pivot >= 0 else -1))
            it['series']['y'].append(s.y.rotation_ratio * (1 if s.y.pivot >= 0 else -1))
            # the 3-D model decides the item (docs/rocking_3d.md): its tilt/alpha of the contact, unsigned
            solid = getattr(s, 'model', '') == 'rocking_3d'
            it['series']['solid'].append(s.rotation_ratio if solid else float('nan'))
            if solid:
                sd = it['solid'] or {'max_ratio': 0.0, 'max_tilt': 0.0, 'contacts': collections.OrderedDict(),
                                     'support_min': None, 'support_final': None}
                sd['max_ratio'] = max(sd['max_ratio'], s.rotation_ratio)
                sd['max_tilt'] = max(sd['max_tilt'], s.tilt)
                if s.contact:
                    sd['contacts'][s.contact] = True
                track_support_margin(sd, getattr(s, 'support_margin', float('nan')))
                it['solid'] = sd
    t_first = None
    for a in data['alarms']:
        it = items.get(a.item_id)
        if it is None:
            continue
        it['description'] = a.description
        it['alarms'][LEVELS.get(a.level, str(a.level))] = {
            'time': a.time_since_first_sample, 'utc': a.event_time, 'plane': a.plane,
            'ratio': a.rotation_ratio, 'predicted_by': list(a.predicted_by), 'not_predicted_by': list(a.not_predicted_by),
            'cause': CAUSES.get(getattr(a, 'cause', 0), 'rocking')}
        t_first = a.event_time - a.time_since_first_sample
        it['left_rest'] = True
    for c in data['criteria']:
        it = items.get(c.item_id)
        if it is not None and c.exceeded:
            it['criteria'].setdefault('%s (%s)' % (c.criterion_name, c.plane), c.header.stamp.to_sec())
    return items, t_first


def track_support_margin(sd, margin):
    """An item on a support (catalogue 'support', docs/rocking_3d.md): the live margin of its centre of mass
    inside the support's nearest edge, m (NaN without a support): the closest it came, and the last."""
    if math.isnan(margin):
        return
    sd['support_min'] = margin if sd['support_min'] is None else min(sd['support_min'], margin)
    sd['support_final'] = margin


def fell_off(it):
    """Whether the item's OVERTURNED alarm says it fell off its support."""
    return it['alarms'].get('OVERTURNED', {}).get('cause') == 'fell_off_support'


def lead_time(it):
    a = it['alarms']
    if 'COMMITTED' in a and 'OVERTURNED' in a:
        return a['OVERTURNED']['time'] - a['COMMITTED']['time']
    return None


def severity(it):
    a = it['alarms']
    level = max([k for k, v in LEVELS.items() if v in a] or [0])
    return (level, max(it['max'].values()))


def health(data):
    """The monitor's own view of its input (diagnostics), per sensor: the last value of each counter and
    the processing time over the event."""
    sensors = collections.OrderedDict()
    catalogue = {}
    series = collections.defaultdict(lambda: {'t': [], 'last': [], 'max': [], 'period': 0.0})
    for m in data['diagnostics']:
        for st in m.status:
            values = {kv.key: kv.value for kv in st.values}
            if st.name.endswith(' samples') and 'received' in values:
                name = st.name.split(': ', 1)[-1]
                sensors[name] = dict(values, summary=st.message, level=ord(st.level) if isinstance(st.level, bytes) else st.level)
                s = series[name]
                s['t'].append(m.header.stamp.to_sec())
                s['last'].append(float(values.get('processing per sample, last (s)', 0)))
                s['max'].append(float(values.get('processing per sample, max (s)', 0)))
                s['period'] = float(values.get('mean sample period (s)', 0))
            elif st.name.endswith('catalogue') and 'items' in values:
                catalogue = values
    return sensors, catalogue, series
