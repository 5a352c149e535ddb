#!/usr/bin/python3
"""Figures of a rocking_study run: analogues of Figures 4-8 of Boroschek & Romo.

    /usr/bin/python3 scripts/plot_study.py STUDY_DIR [--out DIR] [--formats png,svg] [--vertical]

STUDY_DIR holds cases.csv, bodies.csv and summary.json written by rocking_study. Figures:

* figure4_nu0.50, figure5_nu0.30, figure6_nu0.20 (and scatter_nu<e> for any other eccentricity):
  one panel per centre-of-mass height; every case (body x record component x polarity) at
  (PGV of the record, base width B): red circle = overturned, black dot = stayed. Lines are the
  velocity thresholds of the criteria as functions of B (the acceleration part of eq. 2 cannot be
  drawn in this plane): dashed = Ishiyama eq. 2 taking the body as symmetric (nu = 0.5),
  solid = eq. 2 with B' = 2 nu B, dash-dotted = eq. 2 with 0.2 instead of 0.4 (symmetric geometry).
* figure7_overturned_percent: share of cases that overturned versus eccentricity, per height.
* figure8_ratio: that share divided by the symmetric body's, per height (the paper's 2-3.5 at
  nu = 0.3 is drawn for comparison).

By default the cases without the vertical component are plotted (the paper's setting); --vertical
plots the cases with it (only records whose station has a vertical).

Uses Debian's python3-matplotlib and the standard library only. Scatter points are rasterized in
SVG output so the files stay small.
"""

import argparse
import csv
import io
import json
import math
import os
import sys

try:  # Pillow comes with Debian's python3-matplotlib; used only to shrink the PNGs
    from PIL import Image
except ImportError:  # pragma: no cover
    Image = None

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FixedLocator, FuncFormatter, NullLocator  # noqa: E402

G = 9.80665
PAPER_FIGURE = {0.5: "figure4", 0.3: "figure5", 0.2: "figure6"}


def housner_sv(alpha, r):
    """Eq. 1: pseudo-velocity for a 50 % chance of overturning, m/s."""
    return math.sqrt(8.0 / 3.0 * G * r * (1.0 - math.cos(alpha))) / math.cos(alpha)


def ishiyama_v(base, h, coefficient=0.4):
    """Velocity part of eq. 2 for a symmetric block of base `base` and CoM height h."""
    height = 2.0 * h
    return coefficient * housner_sv(math.atan2(base, height), 0.5 * math.hypot(base, height))


def key(x):
    return round(float(x), 9)


def read_cases(path, vertical):
    """Rows of cases.csv reduced to what the figures need."""
    rows = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            if (r["vertical"] == "1") != vertical:
                continue
            rows.append((key(r["eccentricity"]), key(r["cg_height_m"]), float(r["width_m"]),
                         float(r["pgv_mps"]), r["overturned"] == "1", int(r["body"])))
    return rows


def read_bodies(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def check_lines_against_bodies(bodies):
    """The drawn lines must pass through the thresholds rocking_study computed for each body."""
    for b in bodies:
        w, h, e = float(b["width_m"]), float(b["cg_height_m"]), float(b["eccentricity"])
        for name, mine in (("ishiyama_v_mps", ishiyama_v(w, h)),
                           ("ishiyama_equivalent_v_mps", ishiyama_v(2 * e * w, h)),
                           ("proposed_v_mps", ishiyama_v(w, h, 0.2))):
            theirs = float(b[name])
            if abs(mine - theirs) > 1e-6 * max(1.0, theirs):
                sys.exit(f"plot_study: {name} of body {b['body_name']}: {mine} here, {theirs} in bodies.csv")


def save(fig, out, stem, formats):
    paths = []
    for fmt in formats:
        p = os.path.join(out, f"{stem}.{fmt}")
        if fmt == "png" and Image is not None:
            # A 64-colour palette PNG is a third of the size and looks the same (few flat colours).
            buf = io.BytesIO()
            fig.savefig(buf, format="png", dpi=100)
            buf.seek(0)
            with Image.open(buf) as im:
                im.convert("RGB").quantize(colors=64, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE).save(
                    p, optimize=True)
        else:
            # SVG: vector lines and text, scatter rasterized at 90 dpi; no date, so reruns are identical.
            fig.savefig(p, dpi=100 if fmt == "png" else 90, metadata={"Date": None} if fmt == "svg" else None)
        paths.append(p)
    plt.close(fig)
    return paths


def scatter_figure(rows, ecc, heights, out, formats, label):
    n = len(heights)
    ncols = 2 if n > 1 else 1
    nrows = (n + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols, 3.9 * nrows), squeeze=False)
    all_pgv = [r[3] for r in rows if r[3] > 0]
    xlo, xhi = min(all_pgv) / 1.3, max(all_pgv) * 1.3
    for i, h in enumerate(heights):
        ax = axes[i // ncols][i % ncols]
        sel = [r for r in rows if r[0] == ecc and r[1] == h]
        stay = [r for r in sel if not r[4]]
        over = [r for r in sel if r[4]]
        ax.scatter([r[3] for r in stay], [r[2] for r in stay], s=3, c="black", marker=".",
                   linewidths=0, label="stayed", rasterized=True, zorder=2)
        ax.scatter([r[3] for r in over], [r[2] for r in over], s=16, facecolors="none",
                   edgecolors="red", linewidths=0.6, label="overturned", rasterized=True, zorder=3)
        widths = sorted({r[2] for r in sel})
        if widths:
            lo, hi = widths[0], widths[-1]
            bs = [lo * (hi / lo) ** (k / 200.0) for k in range(201)] if hi > lo else [lo]
            ax.plot([ishiyama_v(b, h) for b in bs], bs, "b--", lw=1.3,
                    label="Ishiyama eq. 2 (as symmetric)", zorder=4)
            if ecc < 0.5 - 1e-9:
                ax.plot([ishiyama_v(2 * ecc * b, h) for b in bs], bs, "b-", lw=1.3,
                        label="eq. 2 with B' = 2 nu B", zorder=4)
            ax.plot([ishiyama_v(b, h, 0.2) for b in bs], bs, "g-.", lw=1.3,
                    label="0.2 instead of 0.4", zorder=4)
        pct = 100.0 * len(over) / len(sel) if sel else 0.0
        ax.set_title(f"h = {h:.3g} m: {len(over)} of {len(sel)} cases overturned ({pct:.1f} %)",
                     fontsize=9.5)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(xlo, xhi)
        ticks = [t for t in (0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5) if xlo <= t <= xhi]
        ax.xaxis.set_major_locator(FixedLocator(ticks))
        ax.xaxis.set_minor_locator(NullLocator())
        ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        if widths:
            step = max(1, len(widths) // 6)
            ax.yaxis.set_major_locator(FixedLocator(widths[::step]))
            ax.yaxis.set_minor_locator(NullLocator())
            ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.3g}"))
            ax.set_ylim(widths[0] / 1.12, widths[-1] * 1.12)
        ax.set_xlabel("PGV of the record (m/s)")
        ax.set_ylabel("base width B (m)")
        ax.grid(True, which="major", lw=0.4, alpha=0.5)
        if i == 0:
            handles, labels = ax.get_legend_handles_labels()
    for j in range(n, nrows * ncols):
        axes[j // ncols][j % ncols].axis("off")
    title = "symmetric bodies (nu = 0.5)" if abs(ecc - 0.5) < 1e-9 else f"eccentric bodies, nu = {ecc:.2f}"
    fig.suptitle(f"Overturned (red) and standing (black) {title}\n{label}", fontsize=11)
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=8.5, markerscale=2,
               frameon=False)
    fig.tight_layout(rect=(0, 0.045, 1, 1))
    stem = PAPER_FIGURE.get(round(ecc, 6), "scatter") + f"_nu{ecc:.2f}"
    return save(fig, out, stem, formats)


def curves(summary, set_name):
    s = summary["sets"][set_name]
    eccs, heights = s["eccentricities"], s["cg_heights_m"]
    pct = {(t["eccentricity"], t["cg_height_m"]): t for t in s["by_eccentricity_height"]}
    overall = {t["eccentricity"]: t for t in s["by_eccentricity"]}
    return eccs, heights, pct, overall


def figure7(summary, set_name, out, formats, label):
    eccs, heights, cell, overall = curves(summary, set_name)
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for h in heights:
        ax.plot(eccs, [cell[(e, h)]["overturned_percent"] for e in eccs], "o-", lw=1.2, ms=4,
                label=f"h = {h:.3g} m")
    ax.plot(eccs, [overall[e]["overturned_percent"] for e in eccs], "ks-", lw=2.2, ms=5, label="all heights")
    ax.set_xlim(max(eccs) + 0.02, min(eccs) - 0.02)  # eccentricity grows to the right
    ax.set_xlabel("eccentricity nu (CoM at nu B from the nearer corner; 0.5 = symmetric)")
    ax.set_ylabel("cases overturned (%)")
    ax.set_title(f"Percentage of overturned bodies (Figure 7 analogue)\n{label}", fontsize=10)
    ax.grid(True, lw=0.4, alpha=0.5)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save(fig, out, "figure7_overturned_percent", formats)


def figure8(summary, set_name, out, formats, label):
    eccs, heights, cell, overall = curves(summary, set_name)
    bands = summary["sets"][set_name].get("by_eccentricity_pgv", [])
    fig, axes = plt.subplots(1, 2 if bands else 1, figsize=(12.4 if bands else 6.4, 4.6), squeeze=False)

    def finish(ax, title):
        if any(abs(e - 0.3) < 1e-9 for e in eccs):
            ax.errorbar([0.3], [2.75], yerr=[[0.75], [0.75]], fmt="none", ecolor="red", elinewidth=7,
                        alpha=0.3, capsize=0, label="paper: 2-3.5x at nu = 0.3")
        ax.axhline(1.0, color="gray", lw=0.8)
        ax.set_xlim(max(eccs) + 0.02, min(eccs) - 0.02)
        ax.set_xlabel("eccentricity nu (0.5 = symmetric)")
        ax.set_ylabel("overturned eccentric / overturned symmetric")
        ax.set_title(title, fontsize=10)
        ax.grid(True, lw=0.4, alpha=0.5)
        ax.legend(fontsize=8, loc="upper left")

    def nan(y):
        return math.nan if y is None else y

    ax = axes[0][0]
    for h in heights:
        ax.plot(eccs, [nan(cell[(e, h)]["ratio_to_symmetric"]) for e in eccs], "o-", lw=1.2, ms=4,
                label=f"h = {h:.3g} m")
    ax.plot(eccs, [nan(overall[e]["ratio_to_symmetric"]) for e in eccs], "ks-", lw=2.2, ms=5,
            label="all heights")
    finish(ax, "by height of the centre of mass")
    if bands:
        ax = axes[0][1]
        edges = sorted({(t["pgv_min_mps"], t["pgv_max_mps"] if t["pgv_max_mps"] is not None else math.inf)
                        for t in bands})
        for lo, hi in edges:
            ts = {t["eccentricity"]: t for t in bands if t["pgv_min_mps"] == lo and
                  (t["pgv_max_mps"] if t["pgv_max_mps"] is not None else math.inf) == hi}
            sym = ts.get(0.5)
            if sym is None or sym["overturned"] == 0:
                continue
            name = f"PGV {lo:g}-{hi:g} m/s" if hi < math.inf else f"PGV >= {lo:g} m/s"
            ax.plot(eccs, [nan(ts[e]["ratio_to_symmetric"]) for e in eccs], "o-", lw=1.2, ms=4,
                    label=f"{name}: {sym['overturned']} of {sym['cases']} symmetric cases overturned")
        ax.plot(eccs, [nan(overall[e]["ratio_to_symmetric"]) for e in eccs], "ks-", lw=2.2, ms=5,
                label="all records")
        finish(ax, "by peak ground velocity of the record (log scale)")
        ax.set_yscale("log")
        ax.yaxis.set_major_locator(FixedLocator([1, 2, 3, 5, 10, 20, 50, 100]))
        ax.yaxis.set_minor_locator(NullLocator())
        ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    fig.suptitle(f"Ratio of overturned non-symmetric to symmetric bodies (Figure 8 analogue); {label}",
                 fontsize=10.5)
    fig.tight_layout()
    return save(fig, out, "figure8_ratio", formats)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("study_dir", help="directory written by rocking_study (cases.csv, bodies.csv, summary.json)")
    ap.add_argument("--out", help="where to write the figures (default: STUDY_DIR)")
    ap.add_argument("--formats", default="png,svg", help="comma-separated, e.g. png,svg,pdf")
    ap.add_argument("--vertical", action="store_true",
                    help="plot the cases run with the vertical component (default: without)")
    a = ap.parse_args()
    out = a.out or a.study_dir
    os.makedirs(out, exist_ok=True)
    formats = [f.strip() for f in a.formats.split(",") if f.strip()]
    try:
        with open(os.path.join(a.study_dir, "summary.json")) as f:
            summary = json.load(f)
        bodies = read_bodies(os.path.join(a.study_dir, "bodies.csv"))
        rows = read_cases(os.path.join(a.study_dir, "cases.csv"), a.vertical)
    except (OSError, KeyError, ValueError) as e:
        sys.exit(f"plot_study: {a.study_dir}: {e}")
    if not rows:
        sys.exit("plot_study: no cases " + ("with" if a.vertical else "without") + " the vertical component")
    check_lines_against_bodies(bodies)
    set_name = "vertical_subset_with_vertical" if a.vertical else "horizontal_only"
    label = (f"{summary['records_with_vertical']} components whose station has a vertical, with it"
             if a.vertical else f"{summary['records']} horizontal components, both polarities, no vertical")
    eccs = sorted({r[0] for r in rows}, reverse=True)
    heights = sorted({r[1] for r in rows})
    written = []
    for e in eccs:
        written += scatter_figure(rows, e, heights, out, formats, label)
    if len(eccs) > 1:
        written += figure7(summary, set_name, out, formats, label)
        if any(abs(e - 0.5) < 1e-9 for e in eccs):
            written += figure8(summary, set_name, out, formats, label)
    for p in written:
        print(p)


if __name__ == "__main__":
    main()
