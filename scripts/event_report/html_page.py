"""event_report.html_page: the report as one self-contained HTML page: the banner, the event, the items
table, the figures, the alarm journal and the monitor's health."""
import html
import math
import os
import time

from .analysis import fell_off, ground_motion, health, item_periods, lead_time, severity, summarise_items
from .common import CAUSE_WORDS, G, MAX_ITEM_FIGURES, QUIET_THRESHOLD
from .figures import figure_health, figure_input, figure_item, figure_spectrum


CSS = """
body{font-family:'DejaVu Sans',Arial,sans-serif;margin:24px;color:#222;max-width:1100px}
h1{font-size:22px;margin-bottom:2px} h2{font-size:17px;border-bottom:2px solid #444;margin-top:26px}
h3{font-size:14px;margin:14px 0 2px}
table{border-collapse:collapse;font-size:12px;margin:6px 0} th,td{border:1px solid #bbb;padding:3px 6px;text-align:left}
th{background:#eee} td.num{text-align:right;font-variant-numeric:tabular-nums}
.REST{background:#d9f2d9}.ROCKING{background:#fff3b0}.BEYOND_TIPPING{background:#ffd49a}
.COMMITTED{background:#ff9d9d}.OVERTURNED{background:#d7b5ec;font-weight:bold}
.note{color:#555;font-size:12px} img{max-width:100%}
.banner{background:#b00020;color:#fff;padding:8px 12px;font-weight:bold;margin:8px 0}
@media print{h2{page-break-after:avoid} .item{page-break-inside:avoid}}
"""


def fmt(x, digits=3):
    return '–' if x is None else ('%.*f' % (digits, x))


def seconds(text):
    """A diagnostics value in seconds as people read it: ms or us."""
    try:
        x = float(text)
    except ValueError:
        return html.escape(text)
    return '0' if x == 0 else ('%.3g ms' % (x * 1e3) if x >= 1e-3 else '%.3g µs' % (x * 1e6))


def utc(t):
    if t is None:
        return '–'
    return time.strftime('%Y-%m-%dT%H:%M:%S', time.gmtime(t)) + ('%.3fZ' % (t % 1.0))[1:]


def support_line(sd):
    """The line under an item on a support: how close its centre of mass came to the support's edge."""
    if sd is None or sd['support_min'] is None:
        return ''
    return ('<br><span class="note" data-support-min="%.6f" data-support-final="%.6f">support margin (its centre of '
            'mass inside the support\'s nearest edge): least %.3f m, at the end %.3f m</span>'
            % (sd['support_min'], sd['support_final'], sd['support_min'], sd['support_final']))


def render_journal(journal, w):
    w('<h2 id="journal-section">Alarm journal</h2>')
    w('<p class="note">From <code>%s</code>: %s.</p>' % (html.escape(journal['path']), html.escape(
        'no event' if journal['event'] is None else 'event %s (%s), %d records' % (
            journal['event'], ('closed: the shaking stopped' if journal['records'][-1]['kind'] == 'end' else 'closed by a reset')
            if journal['closed'] else 'not reset', len(journal['records'])))))
    for t in journal['warnings']:
        w('<p class="note" data-journal-warning="1">Warning: %s</p>' % html.escape(t))
    for t in journal['errors']:
        w('<p class="note" data-journal-error="1">Error: %s</p>' % html.escape(t))
    if not journal['records']:
        return
    w('<table id="journal"><tr><th>#</th><th>kind</th><th>item / sensor</th><th>level</th><th>plane</th>'
      '<th>time (UTC)</th><th>since the event\'s first sample, s</th><th>in the bag</th></tr>')
    for r in journal['records']:
        cause = r.get('cause', 'rocking') if r['kind'] == 'alarm' else ''
        level = r.get('level', '–') + (', ' + CAUSE_WORDS[cause] if cause in CAUSE_WORDS else '')
        w('<tr data-sequence="%d" data-kind="%s" data-item="%s" data-level="%s" data-cause="%s" data-plane="%s" '
          'data-since="%.6f" data-in-bag="%s"><td>%d</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td>'
          '<td class="num">%s</td><td>%s</td></tr>' % (r['sequence'], r['kind'], html.escape(r.get('item', '')),
                                r.get('level', ''), html.escape(cause),
                                r.get('plane', ''), r['since_event_start'], 'yes' if r['in_bag'] else 'no',
                                r['sequence'], r['kind'].replace('_', ' '),
                                html.escape(r.get('item') or r.get('sensor', '')), html.escape(level),
                                r.get('plane', '–'), utc(r['time']), fmt(r['since_event_start']),
                                'yes' if r['in_bag'] else 'no: from the journal only'))
    w('</table><p class="note">Times of alarms read from the journal only are seconds since the event\'s first '
      'sample (the items table shows them too, without criteria).</p>')


def catalogue_marks(data, catalogue, items):
    """The catalogue's items (their descriptions into items), their Housner periods to mark on the
    spectrum and the notes about what could not be marked."""
    entries = {}
    cat_items = (catalogue or data.get('catalogue') or {}).get('items') if (catalogue or data.get('catalogue')) else None
    marks, notes = [], []
    for e in cat_items or []:
        entries[str(e.get('id'))] = e
        try:
            for plane, T in item_periods(e).items():
                marks.append((str(e.get('id')), plane, T))
        except (KeyError, ValueError, TypeError) as err:
            notes.append('no Housner period for %s: %s' % (e.get('id'), err))
    if cat_items is None:
        notes.append('no catalogue given (--catalogue): the items\' Housner periods are not marked')
    for i, e in entries.items():
        if i in items and not items[i]['description']:
            items[i]['description'] = str(e.get('description', ''))
    return marks, notes


def render_head(w, data, items, notes, title, ended):
    """The title, the banner of the items that overturned or committed, and the notes."""
    name = title or 'Post-event report'
    w('<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>%s</title><style>%s</style></head><body>'
      % (html.escape(name), CSS))
    w('<h1>%s</h1><p class="note">rocking_monitor · monitor <code>%s</code> · from <code>%s</code> · '
      'written %s</p>' % (html.escape(name), html.escape(data['monitor']), html.escape(os.path.basename(data['bag'])),
                          time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())))
    fallen = [i for i, it in items.items() if 'OVERTURNED' in it['alarms']]
    committed = [i for i, it in items.items() if 'COMMITTED' in it['alarms'] and i not in fallen]
    if fallen or committed:
        named = [i + (' (fell off its support)' if fell_off(items[i]) else '') for i in fallen]
        w('<div class="banner" id="banner">%s</div>' % html.escape(
            '; '.join(x for x in ('Overturned: ' + ', '.join(named) if fallen else '',
                                  'Committed (not seen on its side): ' + ', '.join(committed) if committed else '') if x)))
    if ended:
        w('<p class="note" id="ended">Written automatically when the event ended: %s.</p>' % html.escape(ended))
    for n in notes:
        w('<p class="note">Note: %s</p>' % html.escape(n))
    if data.get('pair'):
        c = data['alarm_copies']
        w('<p class="note" id="pair">Alarms of <code>%s</code> and of its redundant pair <code>%s</code>, each shown '
          'once: %d copies from the other monitor merged, %d received again dropped (docs/journal.md).</p>'
          % (html.escape(data['monitor']), html.escape(data['pair']), c['merged'], c['repeats']))
    if data.get('no_alarm_topic'):
        w('<p class="note">Note: the bag has no <code>%s/alarms</code>: alarm times are missing.</p>' % html.escape(data['monitor']))


def render_event(w, data, gms, t_first, marks, items):
    """The event: each sensor's timing, peaks, input and spectrum."""
    w('<h2 id="event-section">The event</h2>')
    if not gms:
        w('<p class="note">The bag holds no sensor input (sensor_msgs/Imu or geometry_msgs/AccelStamped): '
          'no ground-motion figures.</p>')
    for topic, gm in gms.items():
        render_sensor(w, data, topic, gm, t_first, marks, items)


def render_sensor(w, data, topic, gm, t_first, marks, items):
    """One sensor's part of the event: timing, peaks, the input and the spectrum with the items' periods."""
    start, end = gm['start'], gm['end']
    w('<h3>Sensor <code>%s</code> (%s)</h3>' % (html.escape(topic), data['sensors'][topic]['type']))
    w('<table id="event"><tr><th>first sample</th><td>%s</td></tr>' % utc(gm['t'][0]))
    if start is not None:
        w('<tr><th>shaking starts</th><td data-start="%.6f">%s (%s s after the first sample)</td></tr>'
          % (start - t_first, utc(start), fmt(start - t_first)))
        w('<tr><th>duration</th><td data-duration="%.6f">%s s (first to last sample with |a| ≥ %.2f m/s²)</td></tr>'
          % (end - start, fmt(end - start, 2), QUIET_THRESHOLD))
    else:
        w('<tr><th>shaking</th><td>never above %.2f m/s²</td></tr>' % QUIET_THRESHOLD)
    w('<tr><th>samples</th><td>%d at %.1f Hz over %.2f s</td></tr></table>'
      % (len(gm['t']), 1.0 / gm['dt'] if gm['dt'] > 0 else 0.0, gm['t'][-1] - gm['t'][0]))
    w('<table id="peaks"><tr><th>component (sensor axes)</th><th>PGA, m/s²</th><th>PGA, g</th><th>PGV, m/s</th></tr>')
    for k, comp in enumerate(('x (horizontal)', 'y (horizontal)', 'z (vertical)')):
        w('<tr data-component="%s"><td>%s</td><td class="num" data-pga="%.6f">%.3f</td><td class="num">%.3f</td>'
          '<td class="num" data-pgv="%.6f">%.3f</td></tr>' % ('xyz'[k], comp, gm['pga'][k], gm['pga'][k],
                                                              gm['pga'][k] / G, gm['pgv'][k], gm['pgv'][k]))
    w('</table>')
    w(figure_input(gm, t_first, start, end))
    shown = [m for m in marks if items.get(m[0], {}).get('left_rest') or len(marks) <= 24][:60]
    fig, spectra = figure_spectrum(gm, shown)
    w('<p class="note">5 %%-damped pseudo-acceleration response spectrum of each horizontal (exact '
      'Nigam-Jennings recursion, input linear between samples, over the whole recording); dotted lines: '
      'each item\'s Housner period T = 2π/p (the pivot with the smaller tipping angle), numbered as in '
      'the table below%s.</p>' % ('' if len(shown) == len(marks) else '; only the items that moved are marked'))
    w(fig)
    if shown:
        w('<table id="periods"><tr><th>#</th><th>item</th><th>plane</th><th>Housner period T, s</th>'
          '<th>p, rad/s</th><th>PSA(T) of that plane\'s horizontal, m/s²</th><th>PSV(T), m/s</th></tr>')
        for k, (item, plane, T) in enumerate(shown):
            psa = spectra[plane].get(T)
            w('<tr><td>%d</td><td>%s</td><td>%s</td><td class="num">%.3f</td><td class="num">%.3f</td>'
              '<td class="num">%s</td><td class="num">%s</td></tr>'
              % (k + 1, html.escape(item), plane, T, 2 * math.pi / T, fmt(psa), fmt(None if psa is None else psa * T / (2 * math.pi))))
        w('</table><p class="note">Sensor axes; an item yawed in its catalogue pose sees a rotated '
          'component (the monitor rotates each sample into the item\'s frame).</p>')


def render_items(w, items):
    """The items table and its legend."""
    w('<h2 id="items-section">Items</h2>')
    w('<table id="items"><tr><th>item</th><th>outcome x</th><th>outcome y</th><th>max θ/α x</th><th>max θ/α y</th>'
      '<th>beyond tipping, s</th><th>committed, s</th><th>overturned, s</th><th>warning lead time, s</th>'
      '<th>predicted by</th><th>not predicted by</th></tr>')
    for i, it in items.items():
        w(item_row(i, it))
    w('</table><p class="note">Outcome: each plane\'s mode at the end of the recording (x: rocking across the '
      'width, y: across the depth). Max θ/α over the recorded <code>~states</code> (at the monitor\'s '
      '<code>state_rate</code>; 0 records every sample). Alarm times: seconds since the first sample, with the '
      'plane that reached the level first (UTC on hover; "3d": the 3-D model on the base polygon reached it, '
      'and the line under the item\'s name gives its largest tilt and the base edges and corners it turned about; '
      'for an item on a plinth, shelf or pedestal, the support margin: how far its centre of mass stayed inside '
      'the support\'s edge, m). An OVERTURNED time marked "fell off its support": the item slid or tipped over that edge '
      '(docs/report.md). Lead time: OVERTURNED minus COMMITTED. Criteria: '
      'the screening criteria of that plane that had and had not predicted the item\'s highest alarm.</p>')


def item_row(i, it):
    """One item's row of the items table."""
    a = it['alarms']
    top = a.get('OVERTURNED') or a.get('COMMITTED') or a.get('BEYOND_TIPPING')
    sd = it.get('solid')
    cells = ['<td title="%s"><b>%s</b>%s%s</td>' % (html.escape(it['description']), html.escape(i),
             '' if it['p_overturned'] is None else '<br><span class="note">P(overturned) %.2f [%.2f, %.2f], %d members</span>' % it['p_overturned'],
             '' if sd is None else '<br><span class="note" data-solid-max-ratio="%.6f" data-solid-max-tilt="%.6f">'
             '3-D model deciding: max tilt %.3f rad (θ/α %.2f), turned about %s</span>'
             % (sd['max_ratio'], sd['max_tilt'], sd['max_tilt'], sd['max_ratio'],
                html.escape(', '.join(list(sd['contacts'])[:6]) or 'nothing (stayed flat)'))) + support_line(sd)]
    for plane in ('x', 'y'):
        mode = it['final'].get(plane)
        cells.append('<td class="%s" data-outcome-%s="%s">%s</td>' % (mode or '', plane, mode or '',
                                                                   (mode or '–').lower().replace('_', ' ')))
    for plane in ('x', 'y'):
        cells.append('<td class="num">%s</td>' % (fmt(it['max'][plane], 2) if plane == 'x' or it['planes'] == 2 else '–'))
    for level in ('BEYOND_TIPPING', 'COMMITTED', 'OVERTURNED'):
        al = a.get(level)
        if al:
            cause = CAUSE_WORDS.get(al['cause'])
            cells.append('<td class="num" data-level="%s" data-time="%.6f" data-plane="%s" data-cause="%s" title="%s">'
                         '%s (%s)%s</td>' % (level, al['time'], al['plane'], al['cause'], utc(al['utc']),
                                             fmt(al['time']), al['plane'], '<br>' + cause if cause else ''))
        else:
            cells.append('<td class="num" data-level="%s">–</td>' % level)
    lt = lead_time(it)
    cells.append('<td class="num" data-lead="%s">%s</td>' % ('' if lt is None else '%.6f' % lt, fmt(lt)))
    cells.append('<td data-predicted="%s">%s</td>' % (','.join(top['predicted_by']) if top else '',
                                                       ', '.join(top['predicted_by']) or 'none' if top else '–'))
    cells.append('<td data-not-predicted="%s">%s</td>' % (','.join(top['not_predicted_by']) if top else '',
                                                           ', '.join(top['not_predicted_by']) or 'none' if top else '–'))
    return ('<tr data-item="%s" data-outcome="%s">%s</tr>' % (html.escape(i), it['final'].get('item', ''), ''.join(cells)))


def render_rotations(w, items, t_first):
    """theta/alpha(t) of the items that moved, the most severe first."""
    moving = sorted((it for it in items.values() if it['left_rest']), key=severity, reverse=True)
    w('<h2 id="rotation-section">Rotation of the items that moved</h2>')
    if not moving:
        w('<p>No item left rest.</p>')
    for it in moving[:MAX_ITEM_FIGURES]:
        crit = ', '.join('%s at %s s' % (k, fmt(v - t_first)) for k, v in it['criteria'].items()) or 'none'
        w('<div class="item"><h3>%s <span class="note">%s · criteria exceeded: %s</span></h3>%s</div>'
          % (html.escape(it['id']), html.escape(it['description']), html.escape(crit), figure_item(it, t_first)))
    if len(moving) > MAX_ITEM_FIGURES:
        w('<p class="note">%d more items moved; the table lists them all.</p>' % (len(moving) - MAX_ITEM_FIGURES))
    still = len(items) - len(moving)
    w('<p class="note">%d of %d items stayed at rest throughout.</p>' % (still, len(items)))


def render_health(w, gms, t_first, sensors_h, catalogue_h, proc):
    """The monitor's health during the event, from its /diagnostics, and the bag's own gaps."""
    w('<h2 id="health-section">The monitor\'s health during the event</h2>')
    if not sensors_h:
        w('<p class="note">No <code>/diagnostics</code> from the monitor in the bag.</p>')
    keys = [('received', 'received'), ('accepted', 'accepted'), ('dropped duplicate stamp', 'dropped: duplicate stamp'),
            ('dropped out-of-order stamp', 'dropped: out of order'), ('dropped zero stamp', 'dropped: zero stamp'),
            ('rejected non-finite', 'rejected: non-finite'), ('rejected beyond max_abs_acceleration', 'rejected: beyond limit'),
            ('data gaps (not bridged)', 'data gaps (items frozen, not bridged)'), ('longest gap (s)', 'longest gap, s'), ('resets (time jumped back)', 'resets'),
            ('processing per sample, mean (s)', 'processing per sample, mean, s'),
            ('processing per sample, max (s)', 'processing per sample, max, s'),
            ('mean sample period (s)', 'sample period, s')]
    for name_s, v in sensors_h.items():
        w('<h3>%s — %s</h3><p class="note">As of the last <code>/diagnostics</code> in the bag, %s s after the first '
          'sample (the monitor publishes them once a second).</p><table id="health">'
          % (html.escape(name_s), html.escape(v.get('summary', '')), fmt(proc[name_s]['t'][-1] - t_first, 1)))
        for k, label in keys:
            if k in v:
                w('<tr><th>%s</th><td class="num" data-key="%s" data-value="%s">%s</td></tr>'
                  % (label, html.escape(k), html.escape(v[k]), label.endswith(', s') and seconds(v[k]) or html.escape(v[k])))
        w('</table>')
        w(figure_health(proc[name_s], t_first))
    for topic, gm in gms.items():
        w('<p class="note">In the bag itself (<code>%s</code>): %d gaps longer than 1.5 sample periods (longest %.3f s), '
          '%d stamps not after the previous one.</p>' % (html.escape(topic), gm['gaps'], gm['longest_gap'], gm['non_increasing']))
    if catalogue_h:
        w('<p class="note">Catalogue: %s items, %s alarms published, fidelity %s, method %s.</p>'
          % tuple(html.escape(str(catalogue_h.get(k, '?'))) for k in ('items', 'alarms published', 'fidelity', 'method')))


def render(data, catalogue=None, title=None, ended=None):
    """The whole page, section by section, as one string."""
    items, t_first = summarise_items(data)
    marks, notes = catalogue_marks(data, catalogue, items)
    gms = {t: ground_motion(s) for t, s in data['sensors'].items() if len(s['t']) > 1}
    # The monitor's clock: seconds since the first sample (from its alarms; else the first input stamp).
    if t_first is None:
        t_first = min([g['t'][0] for g in gms.values()] or [data['states'][0].header.stamp.to_sec()])
    sensors_h, catalogue_h, proc = health(data)
    out = []
    w = out.append
    render_head(w, data, items, notes, title, ended)
    render_event(w, data, gms, t_first, marks, items)
    render_items(w, items)
    if data.get('journal') is not None:
        render_journal(data['journal'], w)
    render_rotations(w, items, t_first)
    render_health(w, gms, t_first, sensors_h, catalogue_h, proc)
    w('</body></html>')
    return '\n'.join(out)
