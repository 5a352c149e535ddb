"""plot_performance_common: what plot_performance.py's chart families share (issue 42 split it out).

The matplotlib backend (Agg: no display), the methods' colours and work-precision series, the floor
drawn for zero errors, and the helpers to read a CSV, parse a number and save a chart as PNG + SVG.
"""
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


METHOD_COLOURS = {"dopri5": "#1f77b4", "rk4": "#d62728", "analytic": "#2ca02c",
                  "batch_exact": "#9467bd", "batch_fast": "#ff7f0e"}
# Work-precision series: legend name, marker, marker size (the batch engine runs dopri5 only).
WP_SERIES = {"dopri5": ("dopri5", "o", 5), "batch_exact": ("batch dopri5 (exact trig)", "s", 5),
             "batch_fast": ("batch dopri5 (fast trig)", "^", 6), "rk4": ("rk4", "o", 5),
             "analytic": ("analytic", "*", 11)}
FLOOR = 1e-14  # errors of exactly zero are drawn here


def fnum(x):
    try:
        v = float(x)
    except (TypeError, ValueError):
        return float("nan")
    return v


def save(fig, directory, name):
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(directory, f"{name}.{ext}"), dpi=130, bbox_inches="tight")
    plt.close(fig)
    print(f"  wrote {name}.png/.svg")


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def short_param(method, param):
    p = fnum(param)
    if method in ("dopri5", "batch_exact", "batch_fast"):
        return f"1e{int(round(math.log10(p)))}"
    if method == "rk4":
        return f"{int(p)}"
    return ""
