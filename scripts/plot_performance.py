#!/usr/bin/python3
"""Charts of docs/performance.md from the CSV/JSON written by rocking_accuracy and rocking_benchmarks.

    /usr/bin/python3 scripts/plot_performance.py [--data DIR] [--out docs/performance]

Reads (whatever is present) in the data directory (default: build-bench/performance):
  benchmarks.json          rocking_benchmarks --benchmark_out=... --benchmark_out_format=json
  work_precision.csv       rocking_accuracy work-precision
  overturn_agreement.csv   rocking_accuracy overturn
  stability_map.csv        rocking_accuracy stability
and writes PNG + SVG charts and a markdown summary of the numbers into the output directory:
  cost_per_item_step.*, capacity.*, work_precision_nonlinear.*, work_precision_linearized.*,
  overturn_agreement.*, stability_summary.*, stability_rk4.*, stability_dopri5.*,
  stability_analytic.*, summary.md
A missing data file leaves its charts alone and keeps its sections of the existing summary.md.
Uses Debian's python3-matplotlib only (no pandas).
"""
import argparse
import json
import math
import os
import re
import sys
from collections import defaultdict

# the shared helpers (first: they choose the Agg backend before pyplot loads) and the stability maps
from plot_performance_common import (  # noqa: E402
    FLOOR, METHOD_COLOURS, WP_SERIES, fnum, plt, read_csv, save, short_param)
from plot_performance_stability import plot_stability  # noqa: E402
import matplotlib.ticker  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402


# ----------------------------------------------------------------------------- benchmarks
def parse_benchmarks(path):
    with open(path) as f:
        data = json.load(f)
    out = []
    for b in data.get("benchmarks", []):
        if b.get("run_type") == "aggregate":
            continue
        name = b["name"].split("/min_time")[0].split("/iterations")[0].split("/real_time")[0]
        parts = name.split("/")
        if len(parts) < 4:
            continue
        rec = {
            "kind": parts[0],
            "scenario": parts[1],
            "model": parts[2],
            "method": parts[3],
            "param": parts[4].split(":")[1] if len(parts) > 4 and ":" in parts[4] else "",
        }
        for key in ("ns_per_item_step", "capacity_200Hz", "rocking_frac", "ns_per_rocking",
                    "cap_all_rocking", "int_steps_per_item_step", "impacts", "items",
                    "allocs_per_item_step"):
            if key in b:
                rec[key] = float(b[key])
        out.append(rec)
    return out, data.get("context", {})


def setting_label(r):
    if r["method"] == "dopri5":
        return f"dopri5 {r['param']}"
    if r["method"] == "rk4":
        return f"rk4 x{r['param']}"
    return "analytic"


def plot_benchmarks(directory, rows, context, summary):
    items = [r for r in rows if r["kind"] == "item"]
    if items:
        scenarios = first_seen_scenarios(items)
        plot_item_costs(directory, items, scenarios)
        summarise_item_costs(items, scenarios, summary)

    cats = [r for r in rows if r["kind"] == "catalogue"]
    if cats:
        cases = first_seen_scenarios(cats)
        plot_capacity(directory, cats, cases)
        summarise_capacity(cats, summary)
    if context:
        summary.append(f"Machine: {context.get('num_cpus', '?')} CPUs at {context.get('mhz_per_cpu', '?')} MHz; "
                       f"benchmark run {context.get('date', '')}.\n")


def first_seen_scenarios(rows):
    """The rows' scenarios in the order they first appear."""
    scenarios = []
    for r in rows:
        if r["scenario"] not in scenarios:
            scenarios.append(r["scenario"])
    return scenarios


def plot_item_costs(directory, items, scenarios):
    """cost_per_item_step: ns per item-step by setting and scenario, both models."""
    fig, axes = plt.subplots(2, 2, figsize=(14, 9), squeeze=False)
    for row, (key, ylabel) in enumerate((("ns_per_item_step", "ns per item-step (whole input)"),
                                         ("ns_per_rocking", "ns per item-step in which it rocked"))):
        for col, model in enumerate(("nonlinear", "linearized")):
            ax = axes[row][col]
            sub = [r for r in items if r["model"] == model]
            labels = []
            for r in sub:
                lab = setting_label(r)
                if lab not in labels:
                    labels.append(lab)
            width = 0.8 / max(1, len(scenarios))
            for j, sc in enumerate(scenarios):
                vals = []
                for lab in labels:
                    v = [r.get(key, float("nan")) for r in sub if r["scenario"] == sc and setting_label(r) == lab]
                    vals.append(v[0] if v else float("nan"))
                xs = [i + (j - (len(scenarios) - 1) / 2) * width for i in range(len(labels))]
                ax.bar(xs, vals, width=width, label=sc)
            ax.set_xticks(range(len(labels)))
            ax.set_xticklabels(labels, rotation=50, ha="right", fontsize=8)
            ax.set_ylabel(ylabel)
            if row == 0:
                ax.set_title(f"{model} model, one item, 200 Hz input")
            ax.grid(True, axis="y", alpha=0.3)
            ax.legend(fontsize=7, ncol=2)
    fig.suptitle("Cost of one input sample of one item (Release, one thread); the second row charges "
                 "all the time to the samples in which the item rocked", fontsize=10)
    fig.tight_layout()
    save(fig, directory, "cost_per_item_step")


def summarise_item_costs(items, scenarios, summary):
    summary.append("## Cost per item-step (single item, 200 Hz)\n")
    summary.append("ns per item-step averaged over the whole input; in brackets, per item-step in "
                   "which the item rocked (all time charged to the rocking steps).\n")
    hdr = "| scenario | model | " + " | ".join(labels_all(items)) + " |"
    summary.append(hdr)
    summary.append("|" + "---|" * (2 + len(labels_all(items))))
    for sc in scenarios:
        for model in ("nonlinear", "linearized"):
            cells = []
            for lab in labels_all(items):
                v = [r for r in items if r["scenario"] == sc and r["model"] == model
                     and setting_label(r) == lab]
                if v:
                    r = v[0]
                    cells.append(f"{r['ns_per_item_step']:.0f} ({r.get('ns_per_rocking', float('nan')):.0f})")
                else:
                    cells.append("")
            summary.append(f"| {sc} | {model} | " + " | ".join(cells) + " |")
    summary.append("")


def plot_capacity(directory, cats, cases):
    """capacity: items one core keeps up with at 200 Hz, per catalogue case and setting."""
    labels = []
    for r in cats:
        lab = setting_label(r) + ("" if r["model"] == "nonlinear" else " (lin.)")
        if lab not in labels:
            labels.append(lab)
    fig, axes = plt.subplots(1, len(cases), figsize=(5.2 * len(cases), 5), squeeze=False)
    for ax, case in zip(axes[0], cases):
        sub = [r for r in cats if r["scenario"] == case]
        names = [setting_label(r) + ("" if r["model"] == "nonlinear" else " (lin.)") for r in sub]
        cap = [r["capacity_200Hz"] for r in sub]
        cap_r = [r.get("cap_all_rocking", float("nan")) for r in sub]
        y = range(len(sub))
        ax.barh([i + 0.2 for i in y], cap, height=0.4, color="#1f77b4", label="this input")
        ax.barh([i - 0.2 for i in y], cap_r, height=0.4, color="#ff7f0e",
                label="if every item rocked in every sample")
        ax.axvline(10000, color="k", ls="--", lw=1)
        ax.text(10000, len(sub) - 0.4, " target 10,000", fontsize=7, va="top")
        ax.set_yticks(list(y))
        ax.set_yticklabels(names, fontsize=8)
        ax.set_xscale("log")
        ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:,.0f}"))
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_xlim(min(5000, min(cap_r + cap) * 0.8), max(cap + cap_r) * 2.2)
        ax.set_xlabel("items one core keeps up with at 200 Hz")
        frac = sub[0].get("rocking_frac", float("nan"))
        ax.set_title(f"{case}\n(rocking in {100 * frac:.0f}% of item-steps)", fontsize=9)
        ax.grid(True, axis="x", which="both", alpha=0.3)
        for i, (c, cr) in enumerate(zip(cap, cap_r)):
            ax.text(c, i + 0.2, f" {c:,.0f}", va="center", fontsize=6.5)
            if not math.isnan(cr):
                ax.text(cr, i - 0.2, f" {cr:,.0f}", va="center", fontsize=6.5)
    handles, labs = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labs, loc="lower center", ncol=2, fontsize=8, bbox_to_anchor=(0.5, -0.04))
    fig.suptitle("Real-time capacity of one core (catalogue of 10,000 items, one 200 Hz feed)")
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    save(fig, directory, "capacity")


def summarise_capacity(cats, summary):
    summary.append("## Real-time capacity (10,000-item catalogue, 200 Hz, one core)\n")
    summary.append("| input | method | rocking share | ns/item-step | ns/rocking item-step | "
                   "capacity (this input) | capacity (all rocking) |")
    summary.append("|---|---|---|---|---|---|---|")
    for r in cats:
        summary.append(
            f"| {r['scenario']} | {setting_label(r)} ({r['model']}) | {100 * r.get('rocking_frac', 0):.1f}% "
            f"| {r['ns_per_item_step']:.0f} | {r.get('ns_per_rocking', float('nan')):.0f} "
            f"| {r['capacity_200Hz']:,.0f} | {r.get('cap_all_rocking', float('nan')):,.0f} |")
    summary.append("")


def labels_all(items):
    labels = []
    for r in items:
        lab = setting_label(r)
        if lab not in labels:
            labels.append(lab)
    return labels


# ----------------------------------------------------------------------------- work-precision
def merge_coincident(pts):
    """Consecutive settings with the same error (dopri5 whose steps are capped by the input samples
    does exactly the same work at every tolerance) become one point labelled with the range."""
    out = []
    for x, y, lab in pts:
        if out and abs(out[-1][1] - y) <= 1e-3 * y and 0.5 < out[-1][0][-1] / x < 2.0:
            out[-1][0].append(x)
            out[-1][2].append(lab)
        else:
            out.append(([x], y, [lab]))
    merged = []
    for xs, y, labs in out:
        xs = sorted(xs)
        lab = labs[0] if len(labs) == 1 else f"{labs[0]}..{labs[-1]}"
        merged.append((xs[len(xs) // 2], y, lab))
    return merged


def plot_work_precision(directory, rows, summary):
    kinds = [k for k in ("free", "pulse", "record") if any(r["input"] == k for r in rows)]
    metrics = [("err_peak", "max |theta|/alpha and peaks error (units of alpha)"),
               ("err_impact_s", "impact-time error, first 10 impacts (s)")]
    for model in ("nonlinear", "linearized"):
        sub = [r for r in rows if r["model"] == model]
        if not sub:
            continue
        plot_work_precision_model(directory, sub, model, kinds, metrics)
    summarise_work_precision(rows, summary)


def plot_work_precision_model(directory, sub, model, kinds, metrics):
    """work_precision_MODEL: error against cost, one column per input kind, one row per metric."""
    batch_lanes = {r.get("lanes") for r in sub if r["method"].startswith("batch")}
    lanes = "/".join(sorted(l for l in batch_lanes if l))
    fig, axes = plt.subplots(len(metrics), len(kinds), figsize=(5.0 * len(kinds), 4.2 * len(metrics)),
                             squeeze=False)
    for col, kind in enumerate(kinds):
        kr = [r for r in sub if r["input"] == kind]
        # group by sample rate: free/pulse cases are at 200 or 50 Hz; records at their own rate
        def rate_group(r):
            if kind == "record":
                return "native (100-250 Hz)"
            return f"{int(round(fnum(r['sample_rate_hz'])))} Hz"
        groups = sorted({rate_group(r) for r in kr}, key=lambda g: -fnum(g.split()[0]) if g[0].isdigit() else 0)
        for row, (metric, mlabel) in enumerate(metrics):
            ax = axes[row][col]
            draw_work_precision_panel(ax, kr, groups, rate_group, metric)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_ylim(bottom=FLOOR / 3)
            ax.grid(True, which="both", alpha=0.25)
            if row == 0:
                ax.set_title(f"{kind} input ({model} model)")
            if row == len(metrics) - 1:
                ax.set_xlabel("cost: ns per simulated second (one item)" if not lanes else
                              f"cost: ns per simulated second (one item; batch: per lane of {lanes})")
            if col == 0:
                ax.set_ylabel(mlabel)
    # One legend for the figure (per-panel legends hid the points): colour and marker = method,
    # line style = input rate.
    present = [m for m in WP_SERIES if any(r["method"] == m for r in sub)]
    handles = [Line2D([], [], color=METHOD_COLOURS[m], marker=WP_SERIES[m][1], ms=WP_SERIES[m][2],
                      label=WP_SERIES[m][0]) for m in present]
    handles += [Line2D([], [], color="k", ls="-", label="200 Hz; records at their own rate (100-250 Hz)"),
                Line2D([], [], color="k", ls="--", label="50 Hz")]
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=8,
               bbox_to_anchor=(0.5, -0.035))
    fig.suptitle(f"Work-precision, {model} model: worst error over the cases of each input kind "
                 "(labels: dopri5 tol, rk4 sub-steps; error 0 drawn at 1e-14)"
                 + ("\nbatch dopri5 = BatchRocking, same tolerances; exact trig has the scalar dopri5's "
                    "errors bit for bit" if lanes else ""), fontsize=10)
    fig.tight_layout()
    save(fig, directory, f"work_precision_{model}")


def draw_work_precision_panel(ax, kr, groups, rate_group, metric):
    """One panel: a line per method and input rate, labelled with its settings."""
    for g in groups:
        style = "-" if g.startswith("200") or g.startswith("native") else "--"
        for method, (name, marker, size) in WP_SERIES.items():
            mr = [r for r in kr if r["method"] == method and rate_group(r) == g]
            if not mr:
                continue
            pts = work_precision_points(mr, method, metric)
            if not pts:
                continue
            pts = merge_coincident(pts)
            xs, ys, ls = zip(*pts)
            ax.plot(xs, ys, style, marker=marker, ms=size, color=METHOD_COLOURS[method],
                    label=f"{name}, {g}", alpha=0.9)
            if method.startswith("batch"):
                continue  # same tolerances as the dopri5 labels at the same heights
            for x, y, lab in pts:
                if lab:
                    ax.annotate(lab, (x, y), textcoords="offset points", xytext=(3, 3),
                                fontsize=6, color=METHOD_COLOURS[method])


def work_precision_points(mr, method, metric):
    """(median cost, worst error, label) per setting of one method, in the order its line is drawn."""
    tol_axis = method != "rk4" and method != "analytic"
    by_label = defaultdict(list)
    for r in mr:
        by_label[(fnum(r["param"]), r["label"])].append(r)
    pts = []
    for (param, _label), rs in sorted(by_label.items(), key=lambda kv: -kv[0][0] if tol_axis else kv[0][0]):
        costs = sorted(fnum(r["ns_per_sim_s"]) for r in rs)
        cost = costs[len(costs) // 2]
        errs = [fnum(r[metric]) for r in rs]
        errs = [e for e in errs if not math.isnan(e)]
        if not errs:
            continue
        err = max(errs)
        if math.isinf(err):
            err = 1.0
        pts.append((cost, max(err, FLOOR), short_param(method, param)))
    return pts


def summarise_work_precision(rows, summary):
    summary.append("## Work-precision (worst error over the cases of each kind; cost = median ns per simulated second)\n")
    lanes = sorted({r.get("lanes") for r in rows if r["method"].startswith("batch") and r.get("lanes")})
    if lanes:
        summary.append(f"batch dopri5 rows: `BatchRocking` with {'/'.join(lanes)} identical lanes, cost per lane "
                       "(the batch's time / lanes); exact trig is checked bit-identical to the scalar dopri5 "
                       "by rocking_accuracy.\n")
    summary.append("| model | input | rate | setting | ns/sim-s | ns/item-step | peak err (alpha) | impact err (s) | overturn t err (s) |")
    summary.append("|---|---|---|---|---|---|---|---|---|")
    key = defaultdict(list)
    for r in rows:
        rate = "native" if r["input"] == "record" else f"{int(round(fnum(r['sample_rate_hz'])))}Hz"
        key[(r["model"], r["input"], rate, r["label"])].append(r)
    for (model, kind, rate, label), rs in key.items():
        costs = sorted(fnum(r["ns_per_sim_s"]) for r in rs)
        steps = sorted(fnum(r["ns_per_item_step"]) for r in rs)
        def worst(m):
            v = [fnum(r[m]) for r in rs if not math.isnan(fnum(r[m]))]
            return max(v) if v else float("nan")
        summary.append(f"| {model} | {kind} | {rate} | {label} | {costs[len(costs) // 2]:.3g} | "
                       f"{steps[len(steps) // 2]:.0f} | {worst('err_peak'):.1e} | {worst('err_impact_s'):.1e} | "
                       f"{worst('err_overturn_s'):.1e} |")
    summary.append("")


# ----------------------------------------------------------------------------- overturn agreement
def plot_overturn(directory, rows, summary):
    def tally(reference_key, model_filter):
        stats = defaultdict(lambda: [0, 0, 0, 0])  # runs, different, reference overturned, missed
        for r in rows:
            if r["model"] != model_filter or reference_key not in r:
                continue
            s = stats[r["label"]]
            s[0] += 1
            o, ro = r["overturned"] == "1", r[reference_key] == "1"
            s[1] += o != ro
            s[2] += ro
            s[3] += ro and not o
        return stats

    panels = [("nonlinear methods vs nonlinear reference", tally("ref_overturned", "nonlinear")),
              ("linearized methods vs linearized reference", tally("ref_overturned", "linearized")),
              ("linearized methods vs NONLINEAR reference\n(error of the slender-body model itself)",
               tally("nonlinear_ref_overturned", "linearized"))]
    panels = [p for p in panels if p[1]]

    def order(label):
        m = label.split()[0]
        v = label.split("=")[-1] if "=" in label else "0"
        return ({"dopri5": 0, "rk4": 1, "analytic": 2}[m], -fnum(v) if m == "dopri5" else fnum(v))

    fig, axes = plt.subplots(1, len(panels), figsize=(5.6 * len(panels), 5.8), squeeze=False)
    for ax, (title, stats) in zip(axes[0], panels):
        names = sorted(stats, key=order)
        dis = [stats[n][1] for n in names]
        y = range(len(names))
        ax.barh(list(y), dis, color=[METHOD_COLOURS[n.split()[0]] for n in names])
        for i, n in enumerate(names):
            ax.text(dis[i], i, f" {dis[i]} / {stats[n][0]}", va="center", fontsize=7)
        ax.set_yticks(list(y))
        ax.set_yticklabels(names, fontsize=8)
        ax.invert_yaxis()
        ax.set_xlabel("overturn decisions different from the reference")
        ax.set_title(f"{title}\n({stats[names[0]][2]} of {stats[names[0]][0]} runs overturn in the reference)",
                     fontsize=9)
        ax.set_xlim(0, max(5, max(dis) * 1.35))
        ax.grid(True, axis="x", alpha=0.3)
    fig.suptitle("Overturn decisions over every horizontal .AT2 record (x1 and x2) and 4 bodies; "
                 "reference: dopri5 tol 1e-12")
    fig.tight_layout()
    save(fig, directory, "overturn_agreement")
    summary.append("## Overturn decision agreement (every horizontal .AT2 record at x1 and x2, 4 bodies)\n")
    summary.append("| comparison | setting | runs | reference overturned | different decisions | missed overturns |")
    summary.append("|---|---|---|---|---|---|")
    for title, stats in panels:
        for n in sorted(stats, key=order):
            s = stats[n]
            summary.append(f"| {title.splitlines()[0]} | {n} | {s[0]} | {s[2]} | {s[1]} | {s[3]} |")
    summary.append("")


# Headings of summary.md that each data file produces (see the plot_* functions).
SUMMARY_SECTIONS = {"benchmarks.json": ("## Cost per item-step", "## Real-time capacity"),
                    "work_precision.csv": ("## Work-precision",),
                    "overturn_agreement.csv": ("## Overturn decision agreement",),
                    "stability_map.csv": ("## Stability maps",)}


def kept_sections(path, prefixes):
    """Lines of the sections of an existing summary.md whose headings start with one of prefixes
    (so that regenerating one part, e.g. work-precision alone, keeps the others' numbers)."""
    if not os.path.exists(path):
        return []
    out, keep = [], False
    with open(path) as f:
        for line in f.read().splitlines():
            if line.startswith("## "):
                keep = line.startswith(prefixes)
            if keep:
                out.append(line)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", default="build-bench/performance",
                    help="where rocking_benchmarks/rocking_accuracy wrote their JSON/CSV")
    ap.add_argument("--out", default="docs/performance", help="where the charts go")
    args = ap.parse_args()
    d, out = args.data, args.out
    if not os.path.isdir(d):
        sys.exit(f"plot_performance: no such directory {d}")
    os.makedirs(out, exist_ok=True)
    summary_path = os.path.join(out, "summary.md")
    summary = ["# Performance summary (generated by scripts/plot_performance.py)\n",
               "Numbers behind the charts of this folder; see ../performance.md for their reading.\n"]

    def missing(name):
        kept = kept_sections(summary_path, SUMMARY_SECTIONS[name])
        summary.extend(kept)
        print(f"  ({name} not found: skipped" + ("; its summary sections kept)" if kept else ")"))

    bj = os.path.join(d, "benchmarks.json")
    if os.path.exists(bj):
        rows, ctx = parse_benchmarks(bj)
        plot_benchmarks(out, rows, ctx, summary)
    else:
        missing("benchmarks.json")
    for name, fn in (("work_precision.csv", plot_work_precision),
                     ("overturn_agreement.csv", plot_overturn),
                     ("stability_map.csv", plot_stability)):
        p = os.path.join(d, name)
        if os.path.exists(p):
            fn(out, read_csv(p), summary)
        else:
            missing(name)
    with open(summary_path, "w") as f:
        f.write("\n".join(summary) + "\n")
    print(f"  wrote {os.path.join(out, 'summary.md')}")


if __name__ == "__main__":
    main()
