#!/usr/bin/env python3
"""Explains the wrong predictions of rocking_experiments (docs/validation.md, section 3).

Inputs (all from rocking_experiments):
  --table T.csv       the per-test table of the nominal run (--out)
  --histories DIR     its rotation histories (--histories DIR: TestNNN_SP1.csv per miss)
  --sliding S.csv     optional: the same run with --mu-s LO (the low end of granite-on-steel friction)
  --catalogue Y.yaml  the nominal specimens (alpha of each pivot)
  --tests DIR         the data set's tests/ (raw 800 Hz table acceleration, for its high-frequency share)

Each miss gets the first matching reason of these rules, fixed before any history was looked at:
  1. base contact / centre of mass: overturned in the experiment, but the table never reached the
     model's static uplift g tan(alpha) toward either pivot, or the model never rocked beyond 5 % of
     alpha: the real rock must lift at less, so its pivot lies nearer its centre of mass than the
     model's. (The 5 % clause was added after the first overview showed SP2 misses whose model lifted
     for an instant only; every other rule and threshold was set before any history was drawn.)
  2. sliding: with mu_s = LO (--sliding run) the model's prediction turns into the measured outcome:
     friction at its low end changes the result.
  3. input filtering: predicted overturned but stood, and the raw peak is more than 1.5 x the peak of
     the table acceleration averaged over 25 ms (spikes above ~40 Hz carry the peak that drove the
     model; a real contact and the table's mass filter them).
  4. base contact: predicted overturned but stood, and the model's smaller alpha is below 5 deg: the
     model's pivot sits within 5 deg of the centre of mass, where a scanned base is least certain.
  5. 3-D rocking: every other miss (the planar model rocked; the real rock's out-of-plane motion about
     an oblique base edge is what the planar model lacks). The history's max |theta|/alpha is given.

Writes into --out-dir: a CSV of all misses with their reason (--misses-csv), one overview figure, and
small-multiples pages (12 misses each) per reason (--first-page-only: only the first page of each).
"""
import argparse
import csv
import gzip
import math
import os
import re
import sys

import numpy as np

REASONS = ["base contact / centre of mass", "sliding", "input filtering", "base contact",
           "3-D rocking"]
SLUG = {r: re.sub(r"[^a-z0-9]+", "_", r.lower()).strip("_") for r in REASONS}
COLOUR = {REASONS[0]: "tab:red", REASONS[1]: "tab:green", REASONS[2]: "tab:purple",
          REASONS[3]: "tab:orange", REASONS[4]: "tab:blue"}
G = 9.80665


def read_table(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def alphas(catalogue):
    """{id: (alpha1, alpha2)} in rad from width, cg_height, eccentricity of each item."""
    import yaml
    with open(catalogue) as f:
        items = yaml.safe_load(f)["items"]
    out = {}
    for it in items:
        b, h, nu = float(it["width"]), float(it["cg_height"]), float(it.get("eccentricity", 0.5))
        out[it["id"]] = (math.atan2(nu * b, h), math.atan2((1 - nu) * b, h))
    return out


def hf_ratio(tests_dir, test):
    """Raw peak / peak of the 25 ms moving average of the offset-removed table acceleration."""
    path = os.path.join(tests_dir, f"Test{test:03d}.csv.gz")
    if not os.path.exists(path):
        path = path[:-3]
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as f:
        data = np.loadtxt(f, delimiter=",", skiprows=1)
    t, a = data[:, 0], data[:, 1] - data[:, 1].mean()
    dt = (t[-1] - t[0]) / (len(t) - 1)
    n = max(1, int(round(0.025 / dt)))
    smooth = np.convolve(a, np.ones(n) / n, mode="same")
    return float(np.abs(a).max() / np.abs(smooth).max())


def classify(row, sliding_row, alpha, hf):
    predicted, measured = row["predicted_overturned"] == "1", row["measured_overturned"] == "1"
    if measured and not predicted and (row["exceeds_static_uplift"] == "0" or
                                       float(row["max_rotation_ratio"]) < 0.05):
        return REASONS[0]
    if sliding_row is not None and (sliding_row["predicted_overturned"] == "1") == measured:
        return REASONS[1]
    if predicted and not measured and hf > 1.5:
        return REASONS[2]
    if predicted and not measured and min(alpha) < math.radians(5.0):
        return REASONS[3]
    return REASONS[4]


def read_history(path):
    with open(path) as f:
        r = csv.reader(f)
        header = next(r)
        rows = [x for x in r]
    cols = {name: i for i, name in enumerate(header)}
    arr = np.array([[float(x[cols[c]]) for c in ("t_s", "table_accel_mps2", "theta_rad",
                                                  "rotation_ratio", "max_rotation_ratio")] for x in rows])
    return arr


def draw_miss(ax, m, hist):
    t, a, theta, ratio = hist[:, 0], hist[:, 1] / G, hist[:, 2], hist[:, 3]
    signed = np.where(theta >= 0, ratio, -ratio)  # + rocking on pivot 1, - on pivot 2
    ax.plot(t, a, color="0.65", lw=0.5)
    amax = max(np.abs(a).max(), 1e-3)
    ax.set_ylim(-1.15 * amax, 1.15 * amax)
    ax.tick_params(labelsize=6)
    ax2 = ax.twinx()
    ax2.plot(t, signed, color=COLOUR[m["reason"]], lw=0.8)
    top = max(0.02, min(np.abs(signed).max() * 1.15, 3.0))  # scaled to the rotation, not to alpha
    if top > 1.0:
        for y in (-1, 1):
            ax2.axhline(y, color="k", lw=0.4, ls=":")
    ax2.set_ylim(-top, top)
    ax2.tick_params(labelsize=6, colors=COLOUR[m["reason"]])
    kind = "FP" if m["predicted"] == "1" else "FN"
    rotation = "overturned" if m["predicted"] == "1" else f"max {m['max_ratio']:.2f}"
    ax.set_title(f"Test {m['test']} {m['specimen']} {kind}: peak {m['peak_g']:.2f} g, {rotation}",
                 fontsize=7)


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--table", required=True)
    ap.add_argument("--histories", required=True)
    ap.add_argument("--catalogue", required=True)
    ap.add_argument("--tests", required=True, help="the data set's tests/ directory")
    ap.add_argument("--sliding", help="table of the same run with --mu-s LO")
    ap.add_argument("--out-dir", required=True)
    ap.add_argument("--misses-csv", help="write every miss and its reason here")
    ap.add_argument("--first-page-only", action="store_true")
    ap.add_argument("--per-page", type=int, default=12)
    return ap.parse_args(argv)


def find_misses(a, rows, sliding, al):
    """The wrong predictions with their reasons; and how many of them have no history."""
    misses, missing_hist = [], 0
    for r in rows:
        if r["measured_overturned"] == "" or r["predicted_overturned"] == r["measured_overturned"]:
            continue
        test = int(r["test"])
        hist_path = os.path.join(a.histories, f"Test{test:03d}_{r['specimen']}.csv")
        if not os.path.exists(hist_path):
            missing_hist += 1
            print(f"plot_experiment_misses: no history {hist_path}", file=sys.stderr)
            continue
        hf = hf_ratio(a.tests, test)
        m = {"test": test, "specimen": r["specimen"], "predicted": r["predicted_overturned"],
             "measured": r["measured_overturned"], "peak_g": float(r["peak_table_accel_mps2"]) / G,
             "max_ratio": float(r["max_rotation_ratio"]), "uplift": r["uplift"],
             "exceeds_static_uplift": r["exceeds_static_uplift"], "hf_ratio": hf,
             "reason": classify(r, sliding.get((r["test"], r["specimen"])), al[r["specimen"]], hf),
             "hist": hist_path}
        misses.append(m)
    return misses, missing_hist


def write_misses_csv(path, misses):
    with open(path, "w") as f:
        w = csv.writer(f)
        w.writerow(["test", "specimen", "kind", "peak_table_accel_g", "exceeds_static_uplift",
                    "uplift", "max_rotation_ratio", "hf_peak_ratio", "reason"])
        for m in misses:
            w.writerow([m["test"], m["specimen"], "FP" if m["predicted"] == "1" else "FN",
                        f"{m['peak_g']:.3f}", m["exceeds_static_uplift"], m["uplift"],
                        f"{m['max_ratio']:.3f}", f"{m['hf_ratio']:.2f}", m["reason"]])


def print_reason_counts(misses, specimens):
    """Misses per reason, specimen and kind (FP, FN) to stdout, as CSV."""
    print("reason, " + ", ".join(f"{s} FP, {s} FN" for s in specimens))
    for reason in REASONS:
        cells = []
        for s in specimens:
            for kind in ("1", "0"):
                cells.append(str(sum(1 for m in misses if m["reason"] == reason and m["specimen"] == s
                                     and m["predicted"] == kind)))
        print(f"{reason}, " + ", ".join(cells))


def plot_overview(plt, out_dir, misses, specimens, al):
    """overview.png: peak table acceleration vs the model's max |theta|/alpha, one marker per miss."""
    fig, axes = plt.subplots(1, len(specimens), figsize=(5.2 * len(specimens), 4.0), squeeze=False)
    for ax, s in zip(axes[0], specimens):
        for reason in REASONS:
            for kind, marker in (("1", "x"), ("0", "o")):
                pts = [m for m in misses if m["specimen"] == s and m["reason"] == reason and m["predicted"] == kind]
                if pts:
                    ax.scatter([p["peak_g"] for p in pts], [min(p["max_ratio"], 1.5) for p in pts],
                               marker=marker, s=18, color=COLOUR[reason],
                               facecolors="none" if marker == "o" else None,
                               label=f"{reason} ({'FP' if kind == '1' else 'FN'}, {len(pts)})")
        ax.axhline(1.0, color="k", lw=0.5, ls=":")
        for k, alpha in enumerate(al[s], 1):
            ax.axvline(math.tan(alpha), color="0.5", lw=0.6, ls="--")
        ax.set_xscale("log")
        ax.set_xlabel("peak table acceleration (g); dashed: model's uplift g tan(alpha)")
        ax.set_ylabel("model's max |theta|/alpha (1.5 = overturned)")
        ax.set_title(f"{s}: {sum(1 for m in misses if m['specimen'] == s)} misses (x FP, o FN)")
        ax.legend(fontsize=6, loc="center left")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "overview.png"), dpi=90)
    plt.close(fig)


def plot_reason_pages(plt, a, misses):
    """Small multiples per reason (--per-page misses a page); returns the pages drawn."""
    pages = 0
    for reason in REASONS:
        group = [m for m in misses if m["reason"] == reason]
        for start in range(0, len(group), a.per_page):
            chunk = group[start:start + a.per_page]
            fig, axes = plt.subplots(4, 3, figsize=(11, 9.5))
            for ax in axes.flat[len(chunk):]:
                ax.axis("off")
            for ax, m in zip(axes.flat, chunk):
                draw_miss(ax, m, read_history(m["hist"]))
            fig.suptitle(f"{reason}: misses {start + 1}-{start + len(chunk)} of {len(group)} "
                         f"(grey: table acceleration, g, left axis; colour: theta/alpha, right axis, "
                         f"+ pivot 1, - pivot 2; time s)", fontsize=8)
            fig.tight_layout(rect=(0, 0, 1, 0.97))
            fig.savefig(os.path.join(a.out_dir, f"{SLUG[reason]}_{start // a.per_page + 1}.png"), dpi=72)
            plt.close(fig)
            pages += 1
            if a.first_page_only:
                break
    return pages


def run_misses(a):
    """Classify the misses, write their CSV, print the counts, draw the overview and the pages."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = read_table(a.table)
    sliding = {(r["test"], r["specimen"]): r for r in read_table(a.sliding)} if a.sliding else {}
    al = alphas(a.catalogue)
    misses, missing_hist = find_misses(a, rows, sliding, al)
    if missing_hist:
        print(f"plot_experiment_misses: {missing_hist} misses without a history (not drawn)", file=sys.stderr)
        return 2
    os.makedirs(a.out_dir, exist_ok=True)
    if a.misses_csv:
        write_misses_csv(a.misses_csv, misses)
    # counts
    specimens = sorted({m["specimen"] for m in misses})
    print_reason_counts(misses, specimens)
    plot_overview(plt, a.out_dir, misses, specimens, al)
    pages = plot_reason_pages(plt, a, misses)
    print(f"plot_experiment_misses: {len(misses)} misses, {pages} pages, overview in {a.out_dir}")
    return 0


def main(argv=None):
    return run_misses(parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
