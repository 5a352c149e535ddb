#!/usr/bin/python3
"""calibrate_experiments: calibration of the granite shaking-table predictions with cross-validation.

A grid of model settings (per specimen: geometries from rocking_geometry.py, crossed with runtime
arguments passed through to rocking_experiments) is run once per grid point (cached by a hash of
the settings, at most --jobs processes). Per specimen this gives prediction[grid point, test] and
measured[test]. The fit, on training tests only:

  likelihood: each test's outcome equals the grid point's prediction with probability 1 - e, and is
    the other outcome with probability e (a prediction p in [0, 1] of an ensemble point: P(y = 1) =
    p (1 - e) + (1 - p) e); e is unknown, uniform on (0, 0.5) and integrated on a grid (--e-method
    integrate, default) or maximised per grid point (--e-method max);
  prior: uniform over the distinct grid points (identical catalogue + arguments count once);
  predictive P(overturn) of a test = the posterior-weighted mean of the grid points' predictions,
    label P >= 0.5.

Reported per specimen and for both together: in-sample (fit on all tests), stratified k-fold (fixed
seed) and leave-one-out cross-validated accuracy, precision, recall, F1, Brier; the MAP grid point and
the posterior's top 5. Nothing is tuned per test: a fold's fit sees only its training outcomes.

  calibrate_experiments.py --granite DIR --experiments BIN [--grid grid.json | grid flags]
      --cache-dir DIR --out-dir DIR [--write-catalogue calibrated.yaml]

The grid file (JSON; YAML too where PyYAML is installed):
  {"specimens": {"SP1": {"contact_tolerance_mm": [0.5, 1, 2, 3], "com": ["stated"],
                         "com_shift_mm": [[0, 0]]},
                 "SP2": {"contact_tolerance_mm": [0.5, 1, 2, 3], "com": ["stated", "homogeneous", "urdf"]}},
   "runtime": [[], ["--restitution", "0.8"], ["--restitution", "0.9"]],
   "geometry_args": ["--planar-only"]}
"runtime" is a free-form list of argument lists for rocking_experiments (e.g. ["--model", "3d",
"--restitution-factor", "0.9"]); "geometry_args" go to every rocking_geometry.py call.
Stdlib and numpy only (rocking_geometry.py runs as its own process).
"""
import argparse
import concurrent.futures
import csv
import hashlib
import json
import math
import os
import shlex
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)  # progress_bar.py beside this script, also through a catkin relay
from progress_bar import add_quiet_flag, progress_bar  # noqa: E402

# Runtime flags with an equivalent catalogue key: a calibrated catalogue's members carry them as keys
# (rocking_experiments applies a flag to every member, so members that differ need the key).
RUNTIME_TO_KEY = {"--restitution": "restitution", "--mu-s": "mu_s",
                  "--restitution-factor": "restitution_factor",  # 3-D items only
                  "--table-azimuth": "pose"}  # 3-D: the specimen's yaw on the table, see runtime_keys


def azimuth_pose(value):
    """--table-azimuth A (deg, the table's axis in the specimen's frame) as the specimen's catalogue
    pose: turned by yaw = -A (rad) on the table, which rocking_experiments and the node read alike."""
    yaw = -math.radians(float(value))
    return f"{{parent_frame: table, yaw: {yaw!r}}}   # rad: the table's axis at {float(value):g} deg in the item's frame"


# the fit and the grid (re-exported: ce.fit, ce.parse_grid, ... are used by the tests)
from calibrate_experiments_fit import (  # noqa: E402,F401
    CalibrationError, cross_validate, default_e_grid, evaluate, fit, per_test_loglik, posterior_from_loglik,
    predictive, scores, stratified_folds, support, systematic_resample, with_e)
from calibrate_experiments_grid import (  # noqa: E402,F401
    COM_CANDIDATES, describe, grid_from_flags, load_grid_file, parse_grid)


# ================================================================ running

def sha256_file(path):
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def digest(obj):
    return hashlib.sha256(json.dumps(obj, sort_keys=True).encode()).hexdigest()[:20]


def write_atomic(path, text):
    d = os.path.dirname(path) or "."
    fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp")
    with os.fdopen(fd, "w") as fh:
        fh.write(text)
    os.replace(tmp, path)


def geometry_args(granite, name, geo, extra):
    args = ["--granite", granite, "--specimen", name, "--contact-tolerance", repr(geo["contact_tolerance_m"])]
    if geo["com"] == "homogeneous":
        args.append("--homogeneous")
    elif geo["com"] == "urdf":
        # the centre the Virtual Shake Robot's URDF simulates (SP2: the stated one's opposite). No hull face
        # near SP2's base carries it: settling would lay the rock on its side (72.8 deg), but every test began
        # with it upright. So it stands as placed, and only where the contact tolerance's base polygon
        # carries it (SP2: 1.5 mm and more); elsewhere rocking_geometry refuses it (docs/validation.md).
        args += ["--urdf-com", "--no-settle"]
    if any(geo["com_shift_m"]):
        args += ["--com-shift", repr(geo["com_shift_m"][0]), repr(geo["com_shift_m"][1])]
    return args + list(extra)


def make_geometry(python, tool, granite, name, geo, extra, cache):
    """The specimen's catalogue for this geometry, from the cache or rocking_geometry.py.
    Returns (path, items text without the header, or None and the refusal message)."""
    args = geometry_args(granite, name, geo, extra)
    key = digest({"tool": sha256_file(tool), "granite": os.path.abspath(granite), "args": args})
    path = os.path.join(cache, "geometry", f"{name}_{key}.yaml")
    refused = path + ".refused"
    if os.path.exists(refused):
        with open(refused) as fh:
            return path, None, fh.read()
    if not os.path.exists(path):
        r = subprocess.run([python, tool] + args + ["--yaml", path + ".part"], capture_output=True, text=True)
        if r.returncode == 2:  # the geometry cannot rest (e.g. a shift off the base): not a hypothesis
            write_atomic(refused, r.stderr.strip())
            return path, None, r.stderr.strip()
        if r.returncode != 0:
            raise CalibrationError(f"{tool} {' '.join(args)}: exit {r.returncode}: {r.stderr.strip()}")
        os.replace(path + ".part", path)
    with open(path) as fh:
        text = fh.read()
    return path, "".join(l for l in text.splitlines(True) if not l.startswith("#")), None


def read_table(path, specimen):
    """(test numbers, predicted P, measured) of one specimen from rocking_experiments --out."""
    need = ("test", "specimen", "predicted_overturned", "measured_overturned", "p_overturn")
    tests, p, y = [], [], []
    try:
        with open(path, newline="") as fh:
            rd = csv.DictReader(fh)
            missing = [c for c in need if c not in (rd.fieldnames or [])]
            if missing:
                raise CalibrationError(f"{path}: missing column(s) {', '.join(missing)}")
            for line, row in enumerate(rd, 2):
                if row["specimen"] != specimen:
                    continue
                try:
                    tests.append(int(row["test"]))
                    p.append(float(row["p_overturn"]))
                    y.append(int(row["measured_overturned"]) if row["measured_overturned"] != "" else -1)
                except ValueError:
                    raise CalibrationError(f"{path}:{line}: bad number in test/p_overturn/measured_overturned")
    except OSError as e:
        raise CalibrationError(f"{path}: cannot read ({e})")
    if not tests:
        raise CalibrationError(f"{path}: no rows for specimen {specimen}")
    return np.array(tests), np.array(p), np.array(y)


def data_digest(granite):
    """The data set's identity: outcomes.csv's bytes and the tests' names and sizes."""
    path = os.path.join(granite, "outcomes.csv")
    try:
        listing = sorted((e.name, e.stat().st_size) for e in os.scandir(os.path.join(granite, "tests")))
        return digest({"outcomes": sha256_file(path), "tests": listing})
    except OSError as e:
        raise CalibrationError(f"--granite {granite}: {e}")


def run_point(binary, granite, catalogue, args, cache, binary_hash, catalogue_text, max_tests, data_hash):
    """rocking_experiments on one catalogue with these arguments, cached by a hash of all inputs
    (the binary's bytes, the data set, the catalogue's items, the arguments)."""
    key = digest({"binary": binary_hash, "data": os.path.abspath(granite), "data_hash": data_hash,
                  "catalogue": catalogue_text, "args": list(args), "max_tests": max_tests})
    out = os.path.join(cache, "runs", f"{key}.csv")
    if os.path.exists(out):
        return out, True
    cmd = [binary, granite, "--catalogue", catalogue, "--out", out + ".part"] + list(args)
    if max_tests:
        cmd += ["--max-tests", str(max_tests)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise CalibrationError(f"{' '.join(shlex.quote(c) for c in cmd)}: exit {r.returncode}: "
                               f"{(r.stderr or r.stdout).strip()}")
    write_atomic(os.path.join(cache, "runs", f"{key}.log"), " ".join(shlex.quote(c) for c in cmd) + "\n" + r.stdout)
    os.replace(out + ".part", out)
    return out, False


def build_matrices(grid, a):
    """Runs (or reads from the cache) every grid point; per specimen the prediction matrix, the
    outcomes, the tests, and the distinct grid points (identical catalogue + arguments once)."""
    if not os.path.isfile(a.experiments) or not os.access(a.experiments, os.X_OK):
        raise CalibrationError(f"--experiments {a.experiments}: not an executable (build rocking_experiments first)")
    if not os.path.isdir(os.path.join(a.granite, "tests")):
        raise CalibrationError(f"--granite {a.granite}: no tests/ directory")
    for sub in ("geometry", "runs"):
        os.makedirs(os.path.join(a.cache_dir, sub), exist_ok=True)
    bhash, dhash = sha256_file(a.experiments), data_digest(a.granite)
    tool = os.path.join(HERE, "rocking_geometry.py")
    jobs = []  # (specimen, geo, runtime, catalogue path, items text)
    refused = []
    for name, pts in grid["points"].items():
        seen = {}
        for geo, runtime in pts:
            path, items, why = make_geometry(a.python, tool, a.granite, name, geo, grid["geometry_args"], a.cache_dir)
            if items is None:
                refused.append({"specimen": name, "setting": describe(geo, runtime), "reason": why})
                continue
            key = (items, runtime)
            if key in seen:  # e.g. SP1 has no stated centre: 'homogeneous' is the same model, once
                seen[key][5].append(geo)
                continue
            seen[key] = (name, geo, runtime, path, items, [])
            jobs.append(seen[key])
    t0 = time.time()
    done = {"cached": 0, "run": 0}

    def one(job):
        name, geo, runtime, path, items, _ = job
        args = list(runtime) + grid["common_args"]
        out, cached = run_point(a.experiments, a.granite, path, args, a.cache_dir, bhash, items, a.max_tests, dhash)
        done["cached" if cached else "run"] += 1
        return read_table(out, name)

    tables = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, min(2, a.jobs))) as ex, \
            progress_bar(len(jobs), "calibrate_experiments: grid points", a.quiet) as bar:
        for table in ex.map(one, jobs):  # in job order, as the loop before: the outputs do not change
            tables.append(table)
            bar.update()
    print(f"calibrate_experiments: {len(jobs)} grid points ({done['run']} run, {done['cached']} cached) "
          f"in {time.time() - t0:.0f} s; {len(refused)} geometries refused", file=sys.stderr)
    out = {}
    for (name, geo, runtime, path, items, aliases), (tests, p, y) in zip(jobs, tables):
        s = out.setdefault(name, {"points": [], "rows": [], "tests": tests, "y": y})
        if not np.array_equal(tests, s["tests"]) or not np.array_equal(y, s["y"]):
            raise CalibrationError(f"{name}: grid points ran different tests or read different outcomes")
        s["points"].append({"geometry": geo, "runtime": list(runtime), "catalogue": path, "items": items,
                            "label": describe(geo, runtime, aliases), "same_model_as": aliases})
        s["rows"].append(p)
    for name, s in out.items():
        keep = s["y"] >= 0
        if not keep.all():
            print(f"calibrate_experiments: {name}: {int((~keep).sum())} tests without an outcome left out",
                  file=sys.stderr)
        s["pred"] = np.array(s["rows"])[:, keep]
        s["tests"], s["y"] = s["tests"][keep], s["y"][keep].astype(int)
        del s["rows"]
    return out, refused


# ================================================================ reporting

def top(weights, points, n=5):
    order = np.argsort(-np.asarray(weights), kind="stable")[:n]
    return [{"index": int(k), "weight": float(weights[k]), "setting": points[k]["label"]} for k in order]


def fmt(x, d=3):
    return "-" if x is None else f"{x:.{d}f}"


def markdown(summary):
    lines = [f"Made by: {summary['command']}", "",
             "| specimen | grid points | fit | tests | accuracy | precision | recall | F1 | Brier | Brier (with e) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    rows = list(summary["specimens"].items()) + ([("both", summary["both"])] if "both" in summary else [])
    for name, s in rows:
        for kind, label in (("in_sample", "in-sample"), ("cv", f"{summary['folds']}-fold CV"), ("loo", "leave-one-out")):
            if kind not in s:
                continue
            r = s[kind]
            lines.append(f"| {name} | {s['grid_points']} | {label} | {r['tests']} | {fmt(r['accuracy'])} | "
                         f"{fmt(r['precision'])} | {fmt(r['recall'])} | {fmt(r['f1'])} | {fmt(r['brier'])} | "
                         f"{fmt(r.get('brier_with_e'))} |")
    lines += ["", "| specimen | e (posterior mean) | MAP grid point (its own accuracy) | top 5 (weight) |",
              "|---|---|---|---|"]
    for name, s in summary["specimens"].items():
        t5 = "; ".join(f"{t['setting']} ({t['weight']:.3g})" for t in s["top5"])
        lines.append(f"| {name} | {s['e_mean']:.3f} | {s['map']['setting']} ({s['map']['accuracy']:.3f}) | {t5} |")
    lines += ["", "MAP grid point of each CV fold's fit: " + "; ".join(
        f"{n}: " + ", ".join(str(k) for k in s["cv_map_per_fold"]) for n, s in summary["specimens"].items())]
    return "\n".join(lines) + "\n"


def write_catalogue(path, results, data, command, members, rel, cap, common_args=()):
    """The posterior's support as ensemble members in proportion to weight (rocking_experiments
    counts members unweighted)."""
    head = ["# calibrate_experiments: calibrated catalogue (posterior over the grid, fitted on ALL tests:",
            "# in-sample, not a held-out prediction).",
            f"# made by: {command}",
            f"# Members are drawn in proportion to posterior weight: systematic resampling of the support",
            f"# (weight > {rel:g} of the total, at most {cap} points) to {members} members per specimen, because",
            "# rocking_experiments gives P(overturn) as the unweighted fraction of members.",
            "# Runtime flags of the grid are carried as catalogue keys: " +
            ", ".join(f"{k} -> {v}" for k, v in RUNTIME_TO_KEY.items()) + "."]
    body = []
    common = None
    for name, r in results.items():
        pts = data[name]["points"]
        w = r["fit"]["weights"]
        keep = support(w, rel, cap)
        counts = systematic_resample(w[keep], members)
        j = 0
        for k, n in zip(keep, counts):
            keys, rest = runtime_keys(pts[k]["runtime"], f"{name} grid point {k}")
            if common is None:
                common = rest
            elif rest != common:
                raise CalibrationError(f"--write-catalogue: {name} grid point {k}: runtime arguments "
                                       f"{' '.join(rest)} differ from {' '.join(common)} and have no catalogue key: "
                                       "the members cannot carry them (add the flag to RUNTIME_TO_KEY)")
            item = strip_item(pts[k]["items"])
            if item.count("- id:") != 1:
                raise CalibrationError(f"--write-catalogue: {name} grid point {k}: its catalogue has "
                                       f"{item.count('- id:')} items; members need a single-item geometry")
            for _ in range(int(n)):
                lines = item.replace(f"- id: {name}\n", f"- id: {name}#{j}\n", 1).rstrip("\n").split("\n")
                lines.insert(1, f"    # grid point {k}: {pts[k]['label']}; posterior weight {w[k]:.4f}, "
                                f"{int(n)} of {members} members")
                lines += [f"    {key}: {val}" for key, val in keys]
                body.append("\n".join(lines) + "\n")
                j += 1
    run_with = list(common or []) + list(common_args)
    if run_with:
        head.append("# Run rocking_experiments with these arguments (common to every member): " + " ".join(run_with))
    write_atomic(path, "\n".join(head) + "\nitems:\n" + "".join(body))


def strip_item(items):
    if items.lstrip().startswith("items:"):
        items = items.split("items:", 1)[1].lstrip("\n")
    return items


def runtime_keys(runtime, where):
    keys, rest = [], []
    k = 0
    while k < len(runtime):
        if runtime[k] in RUNTIME_TO_KEY:
            if k + 1 >= len(runtime):
                raise CalibrationError(f"{where}: {runtime[k]} without a value")
            value = runtime[k + 1]
            keys.append((RUNTIME_TO_KEY[runtime[k]],
                         azimuth_pose(value) if runtime[k] == "--table-azimuth" else value))
            k += 2
        else:
            rest.append(runtime[k])
            k += 1
    return keys, rest


def parser():
    """The command line (apart from main, which stays within a screen)."""
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--granite", required=True, metavar="DIR", help="the granite_pbr data set")
    ap.add_argument("--experiments", required=True, metavar="BIN", help="the rocking_experiments executable")
    ap.add_argument("--grid", metavar="FILE", help="the grid (JSON, or YAML with PyYAML); else the flags below")
    ap.add_argument("--specimens", nargs="+", default=["SP1", "SP2"])
    ap.add_argument("--tolerances-mm", nargs="+", type=float, default=[0.5, 1.0, 2.0, 3.0])
    ap.add_argument("--com", nargs="+", default=["stated", "homogeneous"], choices=list(COM_CANDIDATES))
    ap.add_argument("--com-shift-mm", nargs="+", default=["0,0"], metavar="DX,DY")
    ap.add_argument("--runtime", nargs="+", default=[""], metavar="'ARGS'",
                    help="one quoted argument string per runtime setting ('' = the defaults), passed "
                         "to rocking_experiments, e.g. '' '--restitution 0.8' '--model 3d' (a string "
                         "without a space that starts with '-' is taken for a flag: use the grid file)")
    ap.add_argument("--geometry-args", default="", metavar="'ARGS'",
                    help="for every rocking_geometry.py call, e.g. --geometry-args=--planar-only (with '=')")
    ap.add_argument("--common-args", default="", metavar="'ARGS'",
                    help="for every rocking_experiments run, e.g. --common-args='--model 3d' (with '=')")
    ap.add_argument("--cache-dir", required=True)
    ap.add_argument("--out-dir", required=True)
    ap.add_argument("--jobs", type=int, default=2, help="parallel runs (at most 2)")
    ap.add_argument("--folds", type=int, default=10)
    ap.add_argument("--seed", type=int, default=20, help="fold assignment seed")
    ap.add_argument("--e-method", choices=["integrate", "max"], default="integrate")
    ap.add_argument("--no-loo", action="store_true", help="skip leave-one-out")
    ap.add_argument("--max-tests", type=int, default=0, help="only the first N tests (0 = all; for trials)")
    ap.add_argument("--write-catalogue", metavar="FILE")
    ap.add_argument("--members", type=int, default=20, help="members per specimen in --write-catalogue")
    ap.add_argument("--python", default=sys.executable, help="interpreter for rocking_geometry.py")
    add_quiet_flag(ap)
    return ap


def main(argv=None):
    a = parser().parse_args(argv)
    command = " ".join(["calibrate_experiments.py"] + [shlex.quote(x) for x in (sys.argv[1:] if argv is None else argv)])
    try:
        grid = parse_grid(load_grid_file(a.grid), a.grid) if a.grid else parse_grid(grid_from_flags(a), "flags")
        data, refused = build_matrices(grid, a)
        os.makedirs(a.out_dir, exist_ok=True)
        summary = {"command": command, "folds": a.folds, "seed": a.seed, "e_method": a.e_method,
                   "likelihood": "P(outcome = prediction) = 1 - e, e uniform on (0, 0.5); uniform prior over "
                                 "distinct grid points; predictive = posterior-weighted mean of predictions",
                   "refused": refused, "specimens": {}}
        results, all_y = {}, []
        for name, s in data.items():
            r = evaluate(s["pred"], s["y"], a.folds, a.seed, method=a.e_method, loo=not a.no_loo)
            results[name] = r
            w = r["fit"]["weights"]
            acc = (((s["pred"] >= 0.5).astype(int) == s["y"][None, :]).mean(axis=1))
            k = r["fit"]["map"]
            summary["specimens"][name] = {
                "grid_points": len(s["points"]), "tests": int(len(s["y"])), "overturned": int(s["y"].sum()),
                "in_sample": r["in_sample"], "cv": r["cv"], **({"loo": r["loo"]} if "loo" in r else {}),
                "e_mean": r["fit"]["e_mean"], "e_map": r["fit"]["e_map"],
                "map": {"index": k, "setting": s["points"][k]["label"], "weight": float(w[k]),
                        "accuracy": float(acc[k])},
                "top5": top(w, s["points"]),
                "cv_map_per_fold": [f["map"] for f in r["cv_folds"]],
                "points": [{"index": i, "setting": p["label"], "geometry": p["geometry"], "runtime": p["runtime"],
                            "accuracy": float(acc[i]), "weight": float(w[i])} for i, p in enumerate(s["points"])]}
            all_y.append(s["y"])
            with open(os.path.join(a.out_dir, f"predictions_{name}.csv"), "w") as fh:
                fh.write("test,measured,p_in_sample,p_cv,fold" + (",p_loo" if "p_loo" in r else "") + "," +
                         ",".join(f"grid{i}" for i in range(len(s["points"]))) + "\n")
                for j, t in enumerate(s["tests"]):
                    row = [str(t), str(s["y"][j]), f"{r['p_in'][j]:.6f}", f"{r['p_cv'][j]:.6f}", str(r["fold_of_test"][j])]
                    if "p_loo" in r:
                        row.append(f"{r['p_loo'][j]:.6f}")
                    row += [f"{v:g}" for v in s["pred"][:, j]]
                    fh.write(",".join(row) + "\n")
        if len(data) > 1:
            y = np.concatenate(all_y)
            both = {"grid_points": "per specimen"}
            for kind in ("in", "cv", "loo"):
                key = {"in": "in_sample"}.get(kind, kind)
                if all(f"p_{kind}" in r for r in results.values()):
                    both[key] = scores(np.concatenate([results[n][f"p_{kind}"] for n in data]), y)
                    q = np.concatenate([results[n][f"p_{kind}_e"] for n in data])
                    both[key]["brier_with_e"] = float(((q - y) ** 2).mean())
            summary["both"] = both
        with open(os.path.join(a.out_dir, "summary.json"), "w") as fh:
            json.dump(summary, fh, indent=1)
        md = markdown(summary)
        with open(os.path.join(a.out_dir, "summary.md"), "w") as fh:
            fh.write(md)
        sys.stdout.write(md)
        if a.write_catalogue:
            write_catalogue(a.write_catalogue, results, data, command, a.members, 1e-3, 20, grid["common_args"])
            print(f"calibrate_experiments: calibrated catalogue written to {a.write_catalogue}", file=sys.stderr)
    except CalibrationError as e:
        print(f"calibrate_experiments: error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
