#!/usr/bin/env python3
"""One shaking-table test through the planar and the 3-D model, side by side (docs/validation.md).

Inputs: two rotation histories that rocking_experiments wrote for the same test and specimen
(--histories DIR --history-tests N), one run with --model planar and one with --model 3d. Draws the
table acceleration, the planar theta and the 3-D tilt of the base (signed by the side it tips to),
each as a fraction of the tipping angle, and shades the 3-D model's modes (edge rocking, pivoting on
a corner).

  plot_history_planar_vs_3d.py --planar P/Test055_SP2.csv --solid S/Test055_SP2.csv \
      --title "SP2, test 55 (overturned)" --out docs/validation/history_planar_vs_3d.png
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"{path}: no samples")
    for need in ("t_s", "table_accel_mps2", "theta_rad", "rotation_ratio", "mode"):
        if need not in rows[0]:
            raise SystemExit(f"{path}: no column '{need}' (a rocking_experiments --histories file?)")
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--planar", required=True)
    ap.add_argument("--solid", required=True)
    ap.add_argument("--title", default="")
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    # An overturned body has no rotation ratio any more: its history ends at the overturn.
    p = [r for r in read(a.planar) if r["mode"] != "OVERTURNED"]
    s = [r for r in read(a.solid) if r["mode"] != "OVERTURNED"]
    t_p = [float(r["t_s"]) for r in p]
    t_s = [float(r["t_s"]) for r in s]
    fig, (ax0, ax1) = plt.subplots(2, 1, figsize=(10, 6), sharex=True, gridspec_kw={"height_ratios": [1, 2]})
    ax0.plot(t_p, [float(r["table_accel_mps2"]) / 9.80665 for r in p], color="0.3", lw=0.6)
    ax0.set_ylabel("table (g)")
    if a.title:
        ax0.set_title(a.title, fontsize=10)
    sign = lambda r: 1.0 if float(r["theta_rad"]) >= 0.0 else -1.0  # noqa: E731
    ax1.plot(t_p, [sign(r) * float(r["rotation_ratio"]) for r in p], color="tab:blue", lw=1.0,
             label="planar: theta / alpha of the pivot")
    ax1.plot(t_s, [sign(r) * float(r["rotation_ratio"]) for r in s], color="tab:red", lw=1.0,
             label="3-D: rotation towards the edge's or corner's tipping point")
    # Shade the 3-D model's corner wobble.
    start = None
    for r, t in zip(s + [None], t_s + [None]):
        vertex = r is not None and r["mode"] == "VERTEX"
        if vertex and start is None:
            start = t
        if not vertex and start is not None:
            ax1.axvspan(start, t if t is not None else t_s[-1], color="tab:red", alpha=0.08, lw=0)
            start = None
    for y in (1.0, -1.0):
        ax1.axhline(y, color="0.5", ls=":", lw=0.8)
    ax1.set_ylabel("rotation / tipping angle")
    ax1.set_xlabel("time (s)")
    ax1.set_ylim(-2.5, 2.5)
    ax1.legend(loc="upper left", fontsize=8)
    ax1.text(0.99, 0.02, "shaded: 3-D model pivoting on one corner of the base", transform=ax1.transAxes,
             ha="right", fontsize=8, color="tab:red")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
