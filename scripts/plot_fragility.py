#!/usr/bin/python3
"""Plots the fragility curves written by `rocking_study --fragility` (fragility.json and
fragility_runs.csv in one folder): for each body the runs as 0/1 points (overturned or not, against
the scaled record's intensity), the fitted lognormal P(overturn | IM), its 95 % bootstrap band and the
screening criteria's thresholds in the same intensity measure (Ishiyama, B' = 2 nu B, 0.2; Housner
for PSV) as vertical lines.

usage: plot_fragility.py DIR [--out FILE.png] [--bodies NAME ...]
"""
import argparse
import csv
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {"ishiyama": ("tab:red", "-"), "ishiyama_equivalent": ("tab:orange", "--"),
         "proposed": ("tab:purple", ":"), "housner": ("tab:red", "-")}


def phi(x):
    return 0.5 * math.erfc(-x / math.sqrt(2.0))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("dir")
    p.add_argument("--out", default=None)
    p.add_argument("--bodies", nargs="*", default=None)
    a = p.parse_args()
    with open(os.path.join(a.dir, "fragility.json")) as f:
        doc = json.load(f)
    runs = {}
    with open(os.path.join(a.dir, "fragility_runs.csv")) as f:
        reader = csv.DictReader(f)
        im_key = [k for k in reader.fieldnames if k.startswith("im_")][0]
        for row in reader:
            runs.setdefault(row["body"], []).append((float(row[im_key]), int(row["overturned"])))
    bodies = [b for b in doc["bodies"] if a.bodies is None or b["body"] in a.bodies]
    n = len(bodies)
    cols = min(n, 2)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.3 * rows), squeeze=False)
    im, unit = doc["intensity_measure"].upper(), doc["unit"]
    for ax, b in zip([x for r in axes for x in r], bodies):
        pts = runs.get(b["body"], [])
        # 0/1 outcomes, jittered vertically so that the density shows.
        for i, (x, y) in enumerate(pts):
            jitter = ((i * 0.618034) % 1.0 - 0.5) * 0.06
            ax.plot(x, y + jitter, ".", ms=2, color="tab:red" if y else "tab:green", alpha=0.35)
        if b.get("fitted"):
            band = b["band"]
            ax.fill_between(band["im"], band["lower"], band["upper"], color="tab:blue", alpha=0.2,
                            label="95 % bootstrap band")
            xs = band["im"]
            med, beta = b["median"], b["beta"]
            ys = [phi(math.log(x / med) / beta) if beta > 0 else float(x >= med) for x in xs]
            ax.plot(xs, ys, color="tab:blue", lw=2,
                    label="lognormal fit: median %.3g %s, beta %.2f" % (med, unit, beta))
        for name, v in b["thresholds"].items():
            c, ls = STYLE.get(name, ("k", "-"))
            ax.axvline(v, color=c, ls=ls, lw=1.2, label="%s %.3g" % (name.replace("_", " "), v))
        ax.set_xscale("log")
        ax.set_ylim(-0.08, 1.08)
        ax.set_title("%s (%d runs, %d fell)" % (b["body"], b["runs"], b["overturned"]), fontsize=9)
        ax.set_xlabel("%s of the scaled record (%s)" % (im, unit), fontsize=8)
        ax.set_ylabel("P(overturn)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6, loc="upper left")
        ax.grid(True, which="both", alpha=0.3)
    for ax in [x for r in axes for x in r][n:]:
        ax.axis("off")
    fig.suptitle("Fragility (%s); runs as 0/1 points, red = overturned" % doc["model"], fontsize=10)
    fig.tight_layout()
    out = a.out or os.path.join(a.dir, "fragility.png")
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main()
