#!/usr/bin/python3
"""The planar pair's per-axis friction (a square pyramid) against the 3-D model's Coulomb cone (issue 51).

Runs rocking_sim on every station of ../shared/records with both horizontal components and a peak of at
least --min-pga g, for one box that slides before it rocks, with --solid-model planar (each plane its own
full friction) and --solid-model 3d (one isotropic cone), and prints a markdown table and a CSV: the
largest slip along each axis of each (the 3-D model's from its --history-3d), and the slip-onset counts.

  scripts/friction_cone_vs_pyramid.py [--records DIR] [--sim build/devel/lib/rocking_monitor/rocking_sim]
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
from collections import defaultdict

HERE = os.path.dirname(os.path.abspath(__file__))
BOX = ["--width", "0.6", "--depth", "0.5", "--cg-height", "0.35", "--mu-s", "0.3"]


def pairs(records, min_pga):
    """(event, station, file x, file y, peak g) for stations with two horizontals."""
    by_station = defaultdict(list)
    with open(os.path.join(records, "MANIFEST.csv"), newline="") as f:
        for row in csv.DictReader(f):
            if row["component"].startswith("H") and row["format"].startswith("PEER"):
                by_station[(row["event"], row["station"])].append((row["file"], float(row["pga_g"])))
    for (event, station), comps in sorted(by_station.items()):
        if len(comps) >= 2 and max(p for _, p in comps[:2]) >= min_pga:
            yield event, station, comps[0][0], comps[1][0], max(p for _, p in comps[:2])


def run(sim, records, fx, fy, model, history=None):
    extra = ["--history-3d", history] if history else []
    out = subprocess.run([sim, "--record", os.path.join(records, fx), "--record-y", os.path.join(records, fy),
                          *BOX, "--solid-model", model, "--json", *extra], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def axis_maxima(history):
    """The largest |slip| along x and along y in a --history-3d file, m."""
    mx = my = 0.0
    with open(history, newline="") as f:
        for row in csv.DictReader(f):
            mx, my = max(mx, abs(float(row["slip_x_m"]))), max(my, abs(float(row["slip_y_m"])))
    return mx, my


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--records", default=os.path.join(HERE, "..", "..", "shared", "records"))
    ap.add_argument("--sim", default=os.path.join(HERE, "..", "build", "devel", "lib", "rocking_monitor", "rocking_sim"))
    ap.add_argument("--min-pga", type=float, default=0.3, help="g: the stronger horizontal at least this")
    ap.add_argument("--csv", default="friction_cone_vs_pyramid.csv")
    a = ap.parse_args()
    rows = []
    history = "/tmp/friction_cone_vs_pyramid_history.csv"
    for event, station, fx, fy, pga in pairs(a.records, a.min_pga):
        planar, solid = run(a.sim, a.records, fx, fy, "planar"), run(a.sim, a.records, fx, fy, "3d", history)
        px, py = planar["planes"]["x"], planar["planes"]["y"]
        cx, cy = axis_maxima(history)
        rows.append({"event": event, "station": station, "pga_g": pga,
                     "pyramid_x_m": px["max_abs_slip_m"], "pyramid_y_m": py["max_abs_slip_m"],
                     "cone_x_m": cx, "cone_y_m": cy, "cone_max_m": solid["solid"]["max_slip_m"],
                     "pyramid_onsets": px["slip_episodes"] + py["slip_episodes"], "cone_onsets": solid["solid"]["slides"]})
        print(f"{event} {station}: pyramid {px['max_abs_slip_m']:.3f} / {py['max_abs_slip_m']:.3f} m, "
              f"cone {cx:.3f} / {cy:.3f} m", file=sys.stderr)
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print("| record | PGA (g) | pyramid: max slip x / y (m) | cone: max slip x / y (m) | cone: max |slip| (m) | cone / pyramid (x, y) |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        rx = r["cone_x_m"] / r["pyramid_x_m"] if r["pyramid_x_m"] > 1e-4 else float("nan")
        ry = r["cone_y_m"] / r["pyramid_y_m"] if r["pyramid_y_m"] > 1e-4 else float("nan")
        print(f"| {r['event']} {r['station']} | {r['pga_g']:.2f} | {r['pyramid_x_m']:.3f} / {r['pyramid_y_m']:.3f} | "
              f"{r['cone_x_m']:.3f} / {r['cone_y_m']:.3f} | {r['cone_max_m']:.3f} | {rx:.2f}, {ry:.2f} |")


if __name__ == "__main__":
    main()
