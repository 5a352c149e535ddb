#!/usr/bin/python3
"""The planar pair's friction against the 3-D model's Coulomb cone (issue 51).

Runs rocking_sim on every station of ../shared/records with both horizontal components and a peak of at
least --min-pga g, for one box that slides before it rocks: each plane alone (its own full friction, a
square pyramid: the pair before issue 51 part 4), the pair with one shared budget (--solid-model planar,
as the node runs it) and --solid-model 3d (one isotropic cone). Prints a markdown table and a CSV: the
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
PLANE_X = ["--width", "0.6", "--cg-height", "0.35", "--mu-s", "0.3"]  # the box's x plane alone
PLANE_Y = ["--width", "0.5", "--cg-height", "0.35", "--mu-s", "0.3"]  # its y plane alone


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


def alone(sim, records, f, plane):
    """One plane on its own record: its full friction budget."""
    out = subprocess.run([sim, "--record", os.path.join(records, f), *plane, "--json"],
                         capture_output=True, text=True, check=True)
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
        shared, solid = run(a.sim, a.records, fx, fy, "planar"), run(a.sim, a.records, fx, fy, "3d", history)
        px, py = alone(a.sim, a.records, fx, PLANE_X), alone(a.sim, a.records, fy, PLANE_Y)
        sx, sy = shared["planes"]["x"], shared["planes"]["y"]
        cx, cy = axis_maxima(history)
        rows.append({"event": event, "station": station, "pga_g": pga,
                     "pyramid_x_m": px["max_abs_slip_m"], "pyramid_y_m": py["max_abs_slip_m"],
                     "shared_x_m": sx["max_abs_slip_m"], "shared_y_m": sy["max_abs_slip_m"],
                     "cone_x_m": cx, "cone_y_m": cy, "cone_max_m": solid["solid"]["max_slip_m"],
                     "pyramid_onsets": px["slip_episodes"] + py["slip_episodes"],
                     "shared_onsets": sx["slip_episodes"] + sy["slip_episodes"], "cone_onsets": solid["solid"]["slides"]})
        print(f"{event} {station}: pyramid {px['max_abs_slip_m']:.3f} / {py['max_abs_slip_m']:.3f} m, shared "
              f"{sx['max_abs_slip_m']:.3f} / {sy['max_abs_slip_m']:.3f} m, cone {cx:.3f} / {cy:.3f} m", file=sys.stderr)
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print("| record | PGA (g) | planes alone (pyramid): max slip x / y (m) | pair, one budget: x / y (m) | "
          "3-D (cone): x / y (m) | 3-D: max \\|slip\\| (m) |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['event']} {r['station']} | {r['pga_g']:.2f} | {r['pyramid_x_m']:.3f} / {r['pyramid_y_m']:.3f} | "
              f"{r['shared_x_m']:.3f} / {r['shared_y_m']:.3f} | {r['cone_x_m']:.3f} / {r['cone_y_m']:.3f} | "
              f"{r['cone_max_m']:.3f} |")
    for kind in ("pyramid", "shared"):
        err = [abs(r[f"{kind}_{ax}_m"] - r[f"cone_{ax}_m"]) for r in rows for ax in "xy"]
        print(f"{kind}: largest |slip - cone's| {max(err):.3f} m, mean {sum(err) / len(err):.4f} m over {len(err)} "
              "directions")

if __name__ == "__main__":
    main()
