"""event_report.figures: the report's figures (matplotlib, embedded as PNG): the input, the spectrum with
the items' periods, theta/alpha(t) of an item with its alarms, the monitor's processing time."""
import base64
import io
import math

from .analysis import nigam_jennings


def png(fig):
    import matplotlib.pyplot as plt
    buf = io.BytesIO()
    fig.savefig(buf, format='png', dpi=96, bbox_inches='tight')
    plt.close(fig)
    return '<img alt="" src="data:image/png;base64,%s">' % base64.b64encode(buf.getvalue()).decode('ascii')


def figure_input(gm, t0, start, end):
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 1, figsize=(10, 4.2), sharex=True)
    for k, (name, col) in enumerate(zip('xyz', ('tab:blue', 'tab:orange', 'tab:green'))):
        ax[0].plot(gm['t'] - t0, gm['a'][:, k], lw=0.8, color=col, label=name)
        ax[1].plot(gm['t'] - t0, gm['v'][:, k], lw=0.8, color=col, label=name)
    for a in ax:
        if start is not None:
            a.axvspan(start - t0, end - t0, color='0.92', zorder=0)
        a.grid(alpha=0.3)
    ax[0].set_ylabel('acceleration, m/s²')
    ax[1].set_ylabel('velocity, m/s')
    ax[1].set_xlabel('s since the first sample')
    ax[0].legend(loc='upper right', ncol=3, fontsize=8)
    return png(fig)


def figure_spectrum(gm, marks):
    """5 %-damped pseudo-acceleration spectra of both horizontals, the items' Housner periods marked."""
    import numpy as np
    import matplotlib.pyplot as plt
    periods = np.logspace(math.log10(0.05), math.log10(5.0), 120)
    extra = sorted(T for _, _, T in marks if 0.01 < T < 100)
    allp = np.unique(np.concatenate([periods, extra])) if extra else periods
    fig, ax = plt.subplots(figsize=(10, 3.8))
    spectra = {}
    for k, (name, col) in enumerate(zip('xy', ('tab:blue', 'tab:orange'))):
        sd = nigam_jennings(gm['a'][:, k], gm['dt'], allp)
        psa = (2 * np.pi / allp) ** 2 * sd
        spectra[name] = dict(zip(allp, psa))
        ax.plot(allp, psa, color=col, lw=1.2, label='PSA, %s' % name)
    top = max(max(s.values()) for s in spectra.values()) if spectra else 1.0
    for k, (item, plane, T) in enumerate(marks):
        ax.axvline(T, color='0.5', lw=0.6, ls=':')
        ax.text(T, top * (1.04 + 0.1 * (k % 5)), str(k + 1), fontsize=7, va='bottom', ha='center',
                bbox=dict(boxstyle='round,pad=0.15', fc='white', ec='0.6', lw=0.5))
    ax.set_xscale('log')
    ax.set_xlabel('period T, s (Housner period 2π/p of each item and plane marked)')
    ax.set_ylabel('pseudo-acceleration, m/s²')
    ax.set_ylim(0, top * 1.6 if top > 0 else 1)
    ax.set_xlim(periods[0], periods[-1])
    ax.grid(alpha=0.3, which='both')
    ax.legend(loc='upper right', fontsize=8)
    return png(fig), spectra


def figure_item(it, t0):
    import numpy as np
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(10, 2.2))
    t = np.asarray(it['series']['t']) - t0
    if it['planes'] == 2:
        ax.plot(t, it['series']['y'], lw=1.0, color='tab:orange', label='y plane (depth)')
    ax.plot(t, it['series']['x'], lw=1.2, color='tab:blue', label='x plane (width)')
    solid = np.asarray(it['series']['solid'], dtype=float)
    if it.get('solid'):
        ax.plot(t, solid, lw=1.6, color='tab:green', label='3-D model (tilt/α of its contact, deciding)')
    colours = {'BEYOND_TIPPING': 'darkorange', 'COMMITTED': 'red', 'OVERTURNED': 'purple'}
    for level, a in it['alarms'].items():
        ax.axvline(a['time'], color=colours.get(level, 'k'), lw=1.2, ls='--')
        ax.text(a['time'], 1.02 + 0.1 * ['BEYOND_TIPPING', 'COMMITTED', 'OVERTURNED'].index(level) if level in colours else 1.02,
                ' ' + level.lower().replace('_', ' '), color=colours.get(level, 'k'),
                fontsize=7, transform=ax.get_xaxis_transform(), va='bottom')
    for y in (-1, 1):
        ax.axhline(y, color='0.6', lw=0.6, ls=':')
    lim = max(1.3, min(6.0, 1.1 * max(1e-9, np.nanmax(np.abs(np.concatenate(
        [it['series']['x'], it['series']['y'], solid, [0.0]]))))))
    ax.set_ylim(-lim, lim)
    ax.set_ylabel('±θ/α')
    ax.set_xlabel('s since the first sample (±1: tipping angle; + about corner 1)')
    ax.grid(alpha=0.3)
    ax.legend(loc='lower right', fontsize=7, ncol=2)
    return png(fig)


def figure_health(series, t0):
    import matplotlib.pyplot as plt
    if not series['t']:
        return ''
    fig, ax = plt.subplots(figsize=(10, 2.0))
    ms = lambda xs: [1000 * x if x > 0 else float('nan') for x in xs]  # log axis: 0 = not measured yet
    ax.plot([t - t0 for t in series['t']], ms(series['last']), '.-', lw=0.8, label='last sample')
    ax.plot([t - t0 for t in series['t']], ms(series['max']), '.-', lw=0.8, label='max so far')
    if series['period']:
        ax.axhline(1000 * series['period'], color='red', lw=0.8, ls='--', label='sample period')
    ax.set_ylabel('processing, ms')
    ax.set_xlabel('s since the first sample (stamp of the diagnostics message)')
    ax.set_yscale('log')
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc='center right')
    return png(fig)
