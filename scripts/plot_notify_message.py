#!/usr/bin/env python3
"""A picture of an e-mail as the SMTP server received it (docs/notify.md): header and plain text body,
wrapped as a mail client shows them.

  plot_notify_message.py LOG OUT.png [--index N]

LOG: the JSON lines of test/notify/servers.py's SMTP server (one per message received); N: which one
(default: the last).
"""
import argparse
import json
import textwrap

import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402


def main():
    p = argparse.ArgumentParser()
    p.add_argument('log')
    p.add_argument('out')
    p.add_argument('--index', type=int, default=-1)
    a = p.parse_args()
    with open(a.log, encoding='utf-8') as f:
        messages = [json.loads(line) for line in f if line.strip()]
    if not messages:
        raise SystemExit(f'plot_notify_message: {a.log} holds no message')
    m = messages[a.index]
    header = [('From', m['from']), ('To', ', '.join(m['to'])), ('Subject', m['subject'])]
    body = []
    for line in m['body'].replace('\r\n', '\n').split('\n'):
        body += textwrap.wrap(line, 100, subsequent_indent='      ' if line.startswith('  - ') else '') or ['']
    height = 0.3 + 0.19 * (len(header) + len(body) + 1)
    fig = plt.figure(figsize=(9.5, height))
    y = 1.0 - 0.15 / height
    step = 0.19 / height
    for key, value in header:
        fig.text(0.02, y, f'{key}:', fontsize=9, weight='bold', va='top', family='sans-serif')
        fig.text(0.11, y, value, fontsize=9, va='top', family='sans-serif')
        y -= step
    fig.add_artist(plt.Line2D([0.02, 0.98], [y + step * 0.3] * 2, color='0.7', lw=0.8))
    y -= step * 0.5
    for line in body:
        fig.text(0.02, y, line, fontsize=8, va='top', family='monospace')
        y -= step
    fig.savefig(a.out, dpi=110, facecolor='white')


if __name__ == '__main__':
    main()
