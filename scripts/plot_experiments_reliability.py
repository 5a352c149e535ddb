#!/usr/bin/env python3
"""Reliability diagram of rocking_experiments' P(overturn) (its --out CSV with an ensemble catalogue):
observed overturn frequency against predicted probability, per specimen, 5 bins.
  plot_experiments_reliability.py experiments.csv reliability.png"""
import csv
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src, dst):
    rows = [r for r in csv.DictReader(open(src)) if r["measured_overturned"] != ""]
    if not rows:
        sys.exit(f"{src}: no scored rows")
    fig, ax = plt.subplots(figsize=(5.2, 5))
    ax.plot([0, 1], [0, 1], "k:", lw=1, label="perfect reliability")
    for sp, marker in (("SP1", "o"), ("SP2", "s")):
        r = [x for x in rows if x["specimen"] == sp]
        if not r:
            continue
        brier = sum((float(x["p_overturn"]) - int(x["measured_overturned"])) ** 2 for x in r) / len(r)
        xs, ys, ns = [], [], []
        for b in range(5):
            inb = [x for x in r if min(4, int(float(x["p_overturn"]) * 5)) == b]
            if inb:
                xs.append(sum(float(x["p_overturn"]) for x in inb) / len(inb))
                ys.append(sum(int(x["measured_overturned"]) for x in inb) / len(inb))
                ns.append(len(inb))
        ax.plot(xs, ys, marker + "-", label=f"{sp} (Brier {brier:.3f})")
        for x, y, n in zip(xs, ys, ns):
            ax.annotate(str(n), (x, y), textcoords="offset points", xytext=(5, -10), fontsize=7)
    ax.set_xlabel("predicted P(overturn) (bin mean)")
    ax.set_ylabel("observed overturn frequency")
    ax.set_xlim(0, 1)
    ax.set_ylim(-0.02, 1.02)
    ax.set_title("Granite specimens: reliability (numbers: tests per bin)", fontsize=9)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(dst, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
