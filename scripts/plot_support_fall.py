#!/usr/bin/env python3
"""An item on a plinth, shelf or pedestal under a record (docs/rocking_3d.md "Supports that end"):
the plan (the support, the base where it stood and where it ended, the path of its centre of mass)
and the time histories of its slip, its margin to the support's edge and its tilt, from a
`rocking_sim --catalogue ... --solid-model 3d --history-3d` run.

  rocking_sim --catalogue CAT --item ID --record X --record-y Y --solid-model 3d --history-3d h.csv
  scripts/plot_support_fall.py --catalogue CAT --item ID --history h.csv --out fall.png
"""
import argparse
import csv
import math
import textwrap

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402
import yaml  # noqa: E402


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--catalogue', required=True, help='monitor catalogue (YAML) with the item')
    p.add_argument('--item', required=True, help="the item's id (it needs base_polygon and support)")
    p.add_argument('--history', required=True, help="rocking_sim --history-3d's CSV")
    p.add_argument('--title', default='', help='the figure title (default: the item)')
    p.add_argument('--out', required=True, help='PNG to write')
    return p.parse_args()


def load_item(path, item_id):
    with open(path) as f:
        items = yaml.safe_load(f)['items']
    for it in items:
        if it.get('id') == item_id:
            if 'support' not in it or 'base_polygon' not in it:
                raise SystemExit('%s: item %s has no support or no base_polygon' % (path, item_id))
            return it
    raise SystemExit('%s: no item %s' % (path, item_id))


def load_history(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit('%s: no samples' % path)
    return {k: [float(r[k]) if k not in ('model', 'mode') else r[k] for r in rows] for k in rows[0]}


def inside_margin(polygon, x, y):
    """Distance of (x, y) inside the convex counter-clockwise polygon's nearest edge (< 0 beyond)."""
    best = math.inf
    for (ax, ay), (bx, by) in zip(polygon, polygon[1:] + polygon[:1]):
        ex, ey = bx - ax, by - ay
        length = math.hypot(ex, ey)
        best = min(best, (ex * (y - ay) - ey * (x - ax)) / length)  # left of every edge: inside
    return best


def closed(polygon):
    return [p[0] for p in polygon] + [polygon[0][0]], [p[1] for p in polygon] + [polygon[0][1]]


def draw_plan(ax, item, h):
    com = item['centre_of_mass']
    ax.fill(*closed(item['support']), color='0.85', label='support (plinth top)')
    support = item['support']
    for n, k in enumerate(item.get('support_lips', [])):  # numbered from 1: edge k from vertex k to k + 1
        a, b = support[k - 1], support[k % len(support)]
        ax.plot([a[0], b[0]], [a[1], b[1]], color='0.3', lw=3, label='lip' if n == 0 else None)
    ax.plot(*closed(item['base_polygon']), color='tab:blue', label='base at rest')
    # the footprint where it last stood flat (slip only: the yaw is not in the history)
    last = max(i for i, m in enumerate(h['mode']) if m in ('REST', 'SLIDE'))
    sx, sy = h['slip_x_m'][last], h['slip_y_m'][last]
    ax.plot(*closed([[x + sx, y + sy] for x, y in item['base_polygon']]), color='tab:red', ls='--',
            label='base where it last stood or slid flat')
    upto = next((i for i, m in enumerate(h['mode']) if m == 'OVERTURNED'), len(h['mode']))
    ax.plot([com[0] + x for x in h['slip_x_m'][:upto]], [com[1] + y for y in h['slip_y_m'][:upto]], color='k', lw=1,
            label='centre of mass (plan), to the overturn')
    ax.set_aspect('equal')
    ax.set_xlabel('x, m')
    ax.set_ylabel('y, m')
    ax.legend(fontsize=7, loc='upper left')


def draw_histories(axes, item, h):
    com = item['centre_of_mass']
    t = h['time_s']
    slip = [math.hypot(x, y) for x, y in zip(h['slip_x_m'], h['slip_y_m'])]
    margin = [inside_margin(item['support'], com[0] + x, com[1] + y) for x, y in zip(h['slip_x_m'], h['slip_y_m'])]
    mu = item.get('mu_k', item['mu_s'])
    axes[0].plot(t, slip, color='k')
    axes[0].set_ylabel('slip, m')
    axes[1].plot(t, margin, color='tab:green')
    axes[1].axhline(mu * com[2], color='tab:red', ls=':', label='mu_k h: braking would tip it over the edge')
    axes[1].set_ylabel('margin to edge, m')
    axes[1].legend(fontsize=7)
    axes[2].plot(t, h['tilt_rad'], color='tab:blue')
    axes[2].set_ylabel('tilt, rad')
    axes[2].set_xlabel('time, s')
    over = [ti for ti, m in zip(t, h['mode']) if m == 'OVERTURNED']
    for ax in axes:
        if over:  # (after the overturn the state is frozen: the plot stops 2 s later)
            ax.axvline(over[0], color='tab:red', lw=0.8, label='overturned')
            ax.set_xlim(0.0, over[0] + 2.0)


def run(args):
    item = load_item(args.catalogue, args.item)
    h = load_history(args.history)
    fig = plt.figure(figsize=(10, 5.5))
    draw_plan(fig.add_subplot(1, 2, 1), item, h)
    axes = [fig.add_subplot(3, 2, 2 * k + 2) for k in range(3)]
    draw_histories(axes, item, h)
    fig.suptitle('\n'.join(textwrap.wrap(args.title or args.item, 100)), fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)


if __name__ == '__main__':
    run(parse_args())
