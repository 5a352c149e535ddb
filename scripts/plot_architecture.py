#!/usr/bin/env python3
"""Draws docs/architecture/layers.png (and .svg): the layers of the package and the path of one
sample through them. The layer rules themselves live in cmake/layers_rules.cmake; this picture
shows them.  Usage: python3 scripts/plot_architecture.py [OUT_DIR]"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "docs", "architecture")

ROS = "#f6d6b8"
CORE = "#cfe3f5"
BASE = "#e4e4e4"

# name, (x, y) centre, width, colour, contents
LAYERS = {
    "tools": ((2.0, 9.0), 3.4, ROS, "rocking_sim, rocking_study,\nrecord_to_bag"),
    "ros": ((6.0, 9.0), 3.4, ROS, "monitor node / nodelet (one class),\nplayer, catalogue"),
    "study": ((2.0, 7.2), 3.4, CORE, "grid, records, runner,\ncase tables, summary, report"),
    "monitoring": ((6.0, 7.2), 3.4, CORE, "ItemMonitor (two planes, live),\nsimulation (one body, offline)"),
    "model": ((2.0, 5.4), 3.4, CORE, "RockingModel, ContactModel,\nAdaptiveModel"),
    "motion": ((6.0, 5.4), 3.4, CORE, "records (AT2, BBP, SMC, CSV), stations,\nspectra, intensity, baseline"),
    "integrate": ((2.0, 3.6), 3.4, CORE, "dopri5, rk4, analytic steppers,\nevent location, settings"),
    "csv": ((6.0, 3.6), 3.4, CORE, "CSV reading (libcsv)\nand writing"),
    "physics": ((2.0, 1.8), 3.4, CORE, "body, equations of motion, impact,\ncriteria, sliding bound"),
    "constants.hpp": ((6.0, 1.8), 3.4, BASE, "g, pi"),
}
# who uses whom (only the direct, drawn ones; transitive uses are allowed too)
USES = [("tools", "study"), ("tools", "monitoring"), ("ros", "monitoring"), ("ros", "motion"),
        ("study", "model"), ("study", "motion"), ("monitoring", "model"), ("monitoring", "motion"),
        ("model", "integrate"), ("integrate", "physics"), ("motion", "csv"),
        ("physics", "constants.hpp"), ("motion", "constants.hpp")]

PATH = [
    ("sensor_msgs/Imu or AccelStamped", "ros/monitor_sample_path.cpp"),
    ("stamps checked, rotated (tf2), baseline off", "motion/sample_timing, sensor_frame, gravity_baseline"),
    ("item monitor: x and y planes, criteria", "monitoring/item_monitor, plane_monitor"),
    ("adaptive model: rocking or contact", "model/adaptive_model"),
    ("stepper: one input sample", "integrate/dopri5_stepper (rk4, analytic)"),
    ("events: uplift, impact, overturn", "integrate/event_location, physics/impact, criteria"),
    ("state, criteria, alarms published", "ros/monitor_publication.cpp"),
]


def box(ax, centre, width, height, colour, title, body):
    x, y = centre
    ax.add_patch(FancyBboxPatch((x - width / 2, y - height / 2), width, height,
                                boxstyle="round,pad=0.02,rounding_size=0.12", fc=colour, ec="#555555", lw=1.0))
    ax.text(x, y + height / 2 - 0.22, title, ha="center", va="top", fontsize=10, weight="bold")
    ax.text(x, y - 0.12, body, ha="center", va="center", fontsize=7.5)


def arrow(ax, a, b, **kw):
    ax.add_patch(FancyArrowPatch(a, b, arrowstyle="-|>", mutation_scale=11, color=kw.get("color", "#444444"),
                                 lw=kw.get("lw", 0.9), shrinkA=2, shrinkB=2,
                                 connectionstyle=kw.get("cs", "arc3,rad=0.0")))


def main():
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 7.2), gridspec_kw={"width_ratios": [1.05, 1.0]})
    h = 1.25
    for name, (centre, width, colour, body) in LAYERS.items():
        box(left, centre, width, h, colour, name + ("/" if not name.endswith(".hpp") else ""), body)
    for a, b in USES:
        (xa, ya), (xb, yb) = LAYERS[a][0], LAYERS[b][0]
        if abs(xa - xb) < 1e-9 and abs(ya - yb) > 2.0:  # skips a row: around the right side
            arrow(left, (xa + LAYERS[a][1] / 2, ya), (xb + LAYERS[b][1] / 2, yb), cs="arc3,rad=-0.35")
        elif abs(xa - xb) < 1e-9:
            arrow(left, (xa, ya - h / 2), (xb, yb + h / 2))
        else:
            sx = 1 if xb > xa else -1
            arrow(left, (xa + sx * 0.9, ya - h / 2), (xb - sx * 0.9, yb + h / 2))
    left.text(4.0, 10.15, "Layers: an arrow means \"may include and link\"; never upwards",
              ha="center", fontsize=11, weight="bold")
    left.text(4.0, 0.72, "blue: ROS-free core (C++17, Eigen, std), one static library per folder\n"
              "orange: the ROS layer and the command-line tools", ha="center", fontsize=8, color="#333333")
    left.set_xlim(0, 8.6)
    left.set_ylim(0.4, 10.4)
    left.axis("off")

    y = 9.2
    step = 1.3
    for i, (what, where) in enumerate(PATH):
        colour = ROS if where.startswith("ros/") else CORE
        box(right, (3.0, y), 5.4, 0.95, colour, what, "")
        right.text(3.0, y - 0.22, where, ha="center", va="center", fontsize=7.5, family="monospace", color="#1f3f66")
        if i + 1 < len(PATH):
            arrow(right, (3.0, y - 0.5), (3.0, y - step + 0.5), lw=1.4, color="#1f3f66")
        y -= step
    right.text(3.0, 10.15, "The path of one sample (live)", ha="center", fontsize=11, weight="bold")
    right.set_xlim(0, 6)
    right.set_ylim(0.4, 10.4)
    right.axis("off")

    fig.tight_layout()
    os.makedirs(OUT, exist_ok=True)
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(OUT, "layers." + ext), dpi=110)
    print("wrote", os.path.join(OUT, "layers.png"))


if __name__ == "__main__":
    main()
