#!/usr/bin/env python3
"""Accuracy against cost, planar and 3-D (docs/fidelity.md, issue 27).

Left: bidirectional real records (rocking_accuracy planar-vs-3d: boxes on four corners under both
horizontal components x2): per setting, the share of overturn decisions equal to the converged 3-D
model (tol 1e-11; cases where tol 1e-10 decides otherwise are chaotic and left out) against the CPU time
per item-sample. Right: the granite shaking-table tests (accuracy against the real outcomes, planar and
3-D, nothing fitted and calibrated with 10-fold cross-validation) against the CPU time per test.

  plot_planar_vs_3d.py --records docs/fidelity/planar_vs_3d.csv --granite docs/fidelity/granite.json \
      --out docs/fidelity/planar_vs_3d.png
"""
import argparse
import csv
import json
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REFERENCE, CHECK = "3-D tol 1e-11", "3-D tol 1e-10"


def record_points(path):
    rows = list(csv.DictReader(open(path, newline="")))
    if not rows:
        raise SystemExit(f"{path}: no rows")
    by_case = defaultdict(dict)
    cost = defaultdict(lambda: [0.0, 0])
    for r in rows:
        by_case[(r["record"], r["body"])][r["setting"]] = r["overturned"] == "1"
        c = cost[r["setting"]]
        c[0] += float(r["cpu_s"])
        c[1] += int(r["samples"])
    settled = {k: v for k, v in by_case.items() if REFERENCE in v and v.get(CHECK) == v[REFERENCE]}
    chaotic = len(by_case) - len(settled)
    points = []
    for s in sorted(cost):
        if s == REFERENCE:
            continue
        agree = sum(1 for v in settled.values() if v.get(s) == v[REFERENCE])
        points.append((s, 1e9 * cost[s][0] / max(cost[s][1], 1), agree / len(settled), agree, len(settled)))
    overturned = sum(1 for v in settled.values() if v[REFERENCE])
    return points, chaotic, overturned, len(settled)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--records", required=True)
    ap.add_argument("--granite", required=True, help="JSON: [{label, accuracy, cpu_s_per_test, model}]")
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    points, chaotic, overturned, cases = record_points(a.records)
    granite = json.load(open(a.granite))
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(12, 4.8))
    for k, (s, ns, share, agree, n) in enumerate(points):
        colour = "tab:blue" if s.startswith("planar") else "tab:red"
        ax0.scatter([ns], [100 * share], color=colour, s=40)
        ax0.annotate(f"{s}: {agree}/{n}", (ns, 100 * share), textcoords="offset points",
                     xytext=(-150, -14 - 12 * k) if not s.startswith("planar") else (6, 4), fontsize=8)
        print(f"{s:24s} {ns:10.1f} ns/item-sample  agreement {agree}/{n} = {share:.3f}")
    print(f"cases {cases} (+{chaotic} chaotic, left out), overturned in the reference {overturned}")
    ax0.set_xscale("log")
    ax0.set_xlabel("CPU per item-sample (ns, log)")
    ax0.set_ylabel("overturn decisions equal to the converged 3-D model (%)")
    ax0.set_title(f"both horizontal components of 4 near-fault records (as recorded, x0.5):\n"
                  f"{cases} box-record cases, {chaotic} chaotic left out", fontsize=9)
    ax0.grid(True, alpha=0.3)
    for g in granite:
        colour = "tab:blue" if g["model"] == "planar" else "tab:red"
        marker = "o" if "nothing fitted" in g["label"] else "s"
        ax1.scatter([g["cpu_s_per_test"]], [100 * g["accuracy"]], color=colour, marker=marker, s=45)
        ax1.annotate(g["label"], (g["cpu_s_per_test"], 100 * g["accuracy"]), textcoords="offset points",
                     xytext=(6, -4), fontsize=8)
    ax1.axhline(88.5, color="0.5", ls=":", lw=0.8)
    ax1.text(ax1.get_xlim()[0], 88.7, " published 3-D model, calibrated in-sample (0.87 / 0.90)", fontsize=8, color="0.4")
    ax1.set_xlabel("CPU per test and specimen (s)")
    ax1.set_ylabel("accuracy on the 294 real tests, both specimens (%)")
    ax1.set_title("granite shaking-table tests (real outcomes)", fontsize=9)
    ax1.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
