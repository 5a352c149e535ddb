#!/usr/bin/python3
"""Evidence for docs/fidelity.md (issue 7, part 2): cost of rocking-only, contact-only and adaptive
fidelity versus scene intensity, and alarm agreement adaptive vs contact, over the example catalogue.

Runs rocking_sim --json for every catalogue item x scene x fidelity (best of --repeat CPU times),
writes docs/fidelity/cost.csv, docs/fidelity/agreement.csv, docs/fidelity/cost_vs_intensity.png
and the measured tables between the markers in docs/fidelity.md.

usage: scripts/fidelity_evidence.py --sim build-adapt/devel/lib/rocking_monitor/rocking_sim
                                    [--records ../shared/records] [--repeat 3]
                                    [--adaptive-args "--hold-time 0.02"] [--out-dir /tmp/hold_0.02]

--adaptive-args: extra rocking_sim options of every adaptive run (a setting other than the default);
--out-dir: where the CSV and PNG go (default docs/fidelity); docs/fidelity.md is rewritten only with
the default, otherwise the tables are printed.
"""
import argparse
import csv
import json
import math
import os
import random
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# config/catalogue_example.yaml (B, h, nu1, mu_s, extra options)
CATALOGUE = [
    ("medicine_cabinet", ["--width", "0.50", "--cg-height", "0.90", "--eccentricity", "0.40", "--mu-s", "0.6"]),
    ("monitor_cart", ["--width", "0.55", "--cg-height", "0.75", "--mu-s", "0.3"]),
    ("shelving_unit", ["--width", "0.30", "--cg-height", "0.90", "--eccentricity", "0.30", "--mu-s", "0.6"]),
    ("incubator", ["--width", "0.60", "--cg-height", "0.70", "--mu-s", "0.5", "--restitution", "0.92"]),
    ("server_rack", ["--width", "0.60", "--cg-height", "0.95", "--eccentricity", "0.45",
                     "--radius-of-gyration", "0.60", "--mu-s", "0.5"]),
    ("museum_vase", ["--width", "0.15", "--cg-height", "0.35", "--mu-s", "0.6",
                     "--radius-of-gyration", "%.12g" % math.sqrt(0.15 ** 2 / 16 + 0.35 ** 2 / 3)]),
]
FIDELITIES = ["rocking", "contact", "adaptive"]


def quiet_noise_csv(path):
    # 0.005 m/s^2 RMS white noise on x and z, 30 s at 200 Hz (as bags/synthetic_quiet_noise.yaml;
    # Python's generator, not the bag's bit pattern: only the intensity matters here).
    rx, rz = random.Random(1), random.Random(3)
    with open(path, "w") as f:
        f.write("time_s,accel_h_mps2,accel_v_mps2\n")
        for i in range(6001):
            f.write("%.3f,%.9f,%.9f\n" % (i * 0.005, rx.gauss(0, 0.005), rz.gauss(0, 0.005)))


SCENE_RULES_OUT = "friction rules out sliding, slip at impact and flight in the scene envelope"


def run(sim, record, scale, item_args, fidelity, repeat, extra=()):
    best = None
    for _ in range(repeat):
        cmd = [sim, "--record", record, "--scale", str(scale), "--fidelity", fidelity, "--json"] + item_args + list(extra)
        p = subprocess.run(cmd, capture_output=True, text=True, check=True)
        j = json.loads(p.stdout[p.stdout.find("{"):])
        if best is None or j["cpu_time_s"] < best["cpu_time_s"]:
            best = j
    return best


def same_alarms(a, c, tol):
    for k in ("overturned", "committed", "beyond_tipping", "final_mode"):
        if a[k] != c[k]:
            return False, float("inf")
    worst = 0.0
    for k in ("overturn_time_s", "committed_time_s", "beyond_tipping_time_s"):
        x, y = a[k], c[k]
        if (x is None) != (y is None):
            return False, float("inf")
        if x is not None:
            worst = max(worst, abs(x - y))
    return worst <= tol, worst


def parse_args():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--records", default=os.path.join(ROOT, "..", "shared", "records"))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="parallel runs in the sweep")
    ap.add_argument("--sweep-scales", default="0.5,1.0",
                    help="agreement sweep: every .AT2 under --records at these scales ('' = skip)")
    ap.add_argument("--adaptive-args", default="", help="extra rocking_sim options of the adaptive runs")
    ap.add_argument("--out-dir", default=os.path.join(ROOT, "docs", "fidelity"))
    return ap.parse_args()


def intensity_scenes(records):
    """The scenes of the cost table: (level, name, record, scale), quiet noise to full records."""
    tmp = tempfile.mkdtemp()
    noise = os.path.join(tmp, "quiet_noise.csv")
    quiet_noise_csv(noise)
    kobe = os.path.join(records, "kobe_1995", "RSN1106_KOBE_KJM000.AT2")
    elc = os.path.join(records, "imperial_valley_1979", "RSN180_IMPVALL.H_H-E05140.AT2")
    return [
        ("quiet", "quiet noise 0.005 m/s2 RMS (30 s)", noise, 1.0),
        ("moderate", "Kobe KJM000 x0.2", kobe, 0.2),
        ("moderate", "Imperial Valley E05140 x0.2", elc, 0.2),
        ("medium", "Kobe KJM000 x0.5", kobe, 0.5),
        ("medium", "Imperial Valley E05140 x0.5", elc, 0.5),
        ("strong", "Kobe KJM000 x1", kobe, 1.0),
        ("strong", "Imperial Valley E05140 x1", elc, 1.0),
    ]


def run_scenes(args, scenes, adaptive_extra):
    """Every catalogue item x scene x fidelity: the cost rows and the adaptive-vs-contact agreement rows."""
    rows, agree = [], []
    for level, name, record, scale in scenes:
        for item, item_args in CATALOGUE:
            res = {f: run(args.sim, record, scale, item_args, f, args.repeat,
                          adaptive_extra if f == "adaptive" else ()) for f in FIDELITIES}
            n = res["rocking"]["samples"]
            for f in FIDELITIES:
                r = res[f]
                rows.append({
                    "level": level, "scene": name, "item": item, "fidelity": f, "samples": n,
                    "cpu_s": r["cpu_time_s"], "us_per_item_sample": 1e6 * r["cpu_time_s"] / n,
                    "steps": r["steps"], "samples_rocking_model": r["samples_rocking_model"],
                    "samples_contact_model": r["samples_contact_model"],
                    "switches": r["model_switches"], "overturned": r["overturned"]})
            ok, worst = same_alarms(res["adaptive"], res["contact"], 1e-4)
            first = res["adaptive"]["switch_reasons"][0]["reason"] if res["adaptive"]["switch_reasons"] else "-"
            agree.append({"scene": name, "item": item, "agree": ok, "max_time_diff_s": worst,
                          "overturned": res["contact"]["overturned"],
                          "beyond_tipping": res["contact"]["beyond_tipping"],
                          "contact_final_mode": res["contact"]["final_mode"],
                          "rocking_only_overturned": res["rocking"]["overturned"],
                          "switches": res["adaptive"]["model_switches"], "first_reason": first,
                          "ruled_out": res["adaptive"]["initial_model_reason"] == SCENE_RULES_OUT,
                          "required_mu": res["adaptive"]["scene"]["required_mu"]})
            print("%-32s %-17s rock %.3f  contact %.3f  adaptive %.3f us/sample  agree %s" % (
                name, item, *[1e6 * res[f]["cpu_time_s"] / n for f in FIDELITIES], ok), file=sys.stderr)
    return rows, agree


def write_rows(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


LEVELS = ["quiet", "moderate", "medium", "strong"]


def cost_table(rows):
    """{(level, fidelity): (us per item-sample, steps per item-sample, share stepped by ContactModel)}."""
    # Table: mean CPU per item-sample per level and fidelity, plus steps.
    levels = LEVELS
    table = {}
    for lv in levels:
        for fi in FIDELITIES:
            sel = [r for r in rows if r["level"] == lv and r["fidelity"] == fi]
            cpu = sum(r["cpu_s"] for r in sel) / sum(r["samples"] for r in sel)
            steps = sum(r["steps"] for r in sel) / sum(r["samples"] for r in sel)
            rc = sum(r["samples_contact_model"] for r in sel) / sum(r["samples"] for r in sel)
            table[(lv, fi)] = (cpu * 1e6, steps, rc)
    return table


def measured_lines(table, scenes, agree):
    """The markdown tables: cost per intensity level, then agreement per scene and item."""
    levels = LEVELS
    lines = ["| scene intensity | rocking-only us/item-sample | contact-only us/item-sample | adaptive us/item-sample | adaptive / contact | steps per item-sample (rocking / contact / adaptive) | adaptive: share of samples stepped by ContactModel |",
             "|---|---|---|---|---|---|---|"]
    for lv in levels:
        r, c, a = (table[(lv, fi)] for fi in FIDELITIES)
        ratio = a[0] / c[0] if c[0] > 0 else float("nan")
        lines.append("| %s | %.3f | %.3f | %.3f | %.2f | %.2f / %.2f / %.2f | %.1f %% |" % (
            lv, r[0], c[0], a[0], ratio, r[1], c[1], a[1], 100 * a[2]))
    lines += ["", "Scenes: " + "; ".join("%s = %s" % (lv, ", ".join(sorted({s[1] for s in scenes if s[0] == lv})))
                                      for lv in levels) + ".", "",
              "| scene | item | adaptive alarms == contact alarms | max alarm time diff, s | contact: beyond tipping / overturned / final mode | rocking-only overturned | friction the scene can demand (ruled out?) | adaptive switches (first reason) |",
              "|---|---|---|---|---|---|---|---|"]
    for a in agree:
        need = "unbounded" if a["required_mu"] is None else "%.3f" % a["required_mu"]
        lines.append("| %s | %s | %s | %.3g | %s / %s / %s | %s | %s (%s) | %d (%s) |" % (
            a["scene"], a["item"], "yes" if a["agree"] else "**NO**", a["max_time_diff_s"],
            a["beyond_tipping"], a["overturned"], a["contact_final_mode"], a["rocking_only_overturned"],
            need, "yes" if a["ruled_out"] else "no", a["switches"], a["first_reason"]))
    n_ok = sum(a["agree"] for a in agree)
    lines += ["", "Agreement: %d of %d item-scene runs give the same alarms (flags, final mode, times within 1e-4 s)." % (n_ok, len(agree))]
    return lines


def sweep_lines(args, adaptive_extra, out_dir, to_docs):
    """The agreement sweep over every historical record (adaptive vs contact, alarms only): writes
    agreement_sweep.csv, returns its summary lines (none when --sweep-scales is empty)."""
    lines = []
    scales = [float(x) for x in args.sweep_scales.split(",") if x.strip()]
    if scales:
        records = sorted(os.path.join(d, f) for d, _, fs in os.walk(args.records) for f in fs
                         if f.lower().endswith(".at2"))
        def one(job):
            rec, sc, item, item_args = job
            try:
                a = run(args.sim, rec, sc, item_args, "adaptive", 1, adaptive_extra)
                c = run(args.sim, rec, sc, item_args, "contact", 1)
            except subprocess.CalledProcessError:
                return None  # unreadable record (rocking_sim reports it)
            ok, worst = same_alarms(a, c, 1e-4)
            row = {"record": os.path.relpath(rec, args.records), "scale": sc, "item": item,
                   "agree": ok, "max_time_diff_s": worst, "overturned": c["overturned"],
                   "beyond_tipping": c["beyond_tipping"], "switches": a["model_switches"],
                   "ruled_out": a["initial_model_reason"] == SCENE_RULES_OUT,
                   "adaptive_steps": a["steps"], "contact_steps": c["steps"],
                   "adaptive_cpu_s": a["cpu_time_s"], "contact_cpu_s": c["cpu_time_s"],
                   "contact_self_agree_x4_substeps": ""}
            if not ok:
                # Is always-contact itself that sensitive? Same model, 4x the RK4 sub-steps.
                c4 = run(args.sim, rec, sc, item_args, "contact", 1, ["--contact-substeps", "64"])
                row["contact_self_agree_x4_substeps"] = same_alarms(c, c4, 1e-4)[0]
            return row
        from concurrent.futures import ThreadPoolExecutor
        jobs = [(rec, sc, item, item_args) for rec in records for sc in scales for item, item_args in CATALOGUE]
        with ThreadPoolExecutor(max_workers=args.jobs) as pool:
            sweep = [r for r in pool.map(one, jobs) if r is not None]
        with open(os.path.join(out_dir, "agreement_sweep.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(sweep[0].keys()))
            w.writeheader()
            w.writerows(sweep)
        bad = [x for x in sweep if not x["agree"]]
        lines += ["", "Sweep: %d historical records x scales %s x 6 items = %d runs: adaptive alarms == contact alarms in %d "
                  "(%d with beyond tipping, %d overturned, %d with at least one switch, %d switches in all, %d where the record's own envelope "
                  "rules the contact model out); max alarm time difference %.3g s; "
                  "integrator steps adaptive / contact = %.3f; CPU adaptive / contact = %.3f "
                  "(%s)." % (
                      len({x["record"] for x in sweep}), ",".join("x%g" % s for s in scales), len(sweep),
                      len(sweep) - len(bad), sum(x["beyond_tipping"] for x in sweep),
                      sum(x["overturned"] for x in sweep), sum(x["switches"] > 0 for x in sweep), sum(x["switches"] for x in sweep),
                      sum(x["ruled_out"] for x in sweep),
                      max([x["max_time_diff_s"] for x in sweep if x["agree"]] + [0.0]),
                      sum(x["adaptive_steps"] for x in sweep) / max(1, sum(x["contact_steps"] for x in sweep)),
                      sum(x["adaptive_cpu_s"] for x in sweep) / max(1e-12, sum(x["contact_cpu_s"] for x in sweep)),
                      "docs/fidelity/agreement_sweep.csv" if to_docs else os.path.join(out_dir, "agreement_sweep.csv"))]
        for x in bad:
            lines.append("* disagreement: %s x%g %s (max time diff %.3g s; always-contact with 64 instead of 16 "
                         "sub-steps per sample %s itself)" % (
                             x["record"], x["scale"], x["item"], x["max_time_diff_s"],
                             "agrees with" if x["contact_self_agree_x4_substeps"] else "**differs from**"))
    return lines


def rewrite_fidelity_md(lines):
    """The measured tables between the markers of docs/fidelity.md."""
    md = os.path.join(ROOT, "docs", "fidelity.md")
    text = open(md).read()
    b, e = "<!-- measured:begin -->", "<!-- measured:end -->"
    text = text[:text.index(b) + len(b)] + "\n" + "\n".join(lines) + "\n" + text[text.index(e):]
    open(md, "w").write(text)


def plot_cost_vs_intensity(table, out_dir):
    levels = LEVELS
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.2))
    x = range(len(levels))
    width = 0.26
    for k, fi in enumerate(FIDELITIES):
        ax.bar([i + (k - 1) * width for i in x], [table[(lv, fi)][0] for lv in levels], width, label=fi)
    ax.set_xticks(list(x))
    ax.set_xticklabels(["quiet\n(noise 0.005 m/s2)", "moderate\n(records x0.2)", "medium\n(records x0.5)",
                        "strong\n(records x1)"])
    ax.set_yscale("log")
    ax.set_ylabel("CPU time per item-sample, us")
    ax.set_title("Cost vs scene intensity, example catalogue (6 items)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "cost_vs_intensity.png"), dpi=110)


def run_evidence(args):
    """Cost and agreement runs, their CSVs, tables and chart (module docstring)."""
    out_dir = args.out_dir
    to_docs = os.path.abspath(out_dir) == os.path.join(ROOT, "docs", "fidelity")
    adaptive_extra = args.adaptive_args.split()
    os.makedirs(out_dir, exist_ok=True)
    scenes = intensity_scenes(args.records)
    rows, agree = run_scenes(args, scenes, adaptive_extra)
    write_rows(os.path.join(out_dir, "cost.csv"), rows)
    write_rows(os.path.join(out_dir, "agreement.csv"), agree)
    table = cost_table(rows)
    lines = measured_lines(table, scenes, agree)
    lines += sweep_lines(args, adaptive_extra, out_dir, to_docs)
    if to_docs:
        rewrite_fidelity_md(lines)
    plot_cost_vs_intensity(table, out_dir)
    print("\n".join(lines))


def main():
    run_evidence(parse_args())


if __name__ == "__main__":
    main()
