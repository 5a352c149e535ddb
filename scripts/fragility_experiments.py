#!/usr/bin/python3
"""fragility_experiments: a calibrated P(overturn) per shaking-table test (issue 41), judged on held-out tests.

For each specimen of a calibrated catalogue (calibrate_experiments.py --write-catalogue: members SP1#0..;
or a fragility catalogue this script wrote: its input_gain and ensemble_size are set aside) and each
distinct member body, the margin of every test: the smallest scale s* of the test's table motion at
which the model overturns (`rocking_experiments --margins`: 17 scales from 0.25 to 4, then 5 halvings
of ln s; tests whose outcome is not monotone in s are counted as chaotic). Cached on disk by the
rocking_experiments binary's bytes, the member's catalogue text, the data set and the search.

The fragility (an earthquake engineer's lognormal fragility in the input scale):
  P(overturn | test) = sum over members m of w_m Phi(-(ln s*_m + mu) / beta)
i.e. the real rock overturns when the model at scale exp(eps) would, eps ~ N(-mu, beta) (the model's
bias and the spread of real outcomes near its boundary). mu and beta are fitted by maximum likelihood
on the training tests only; evaluated by stratified k-fold CV (the folds of calibrate_experiments.py:
same function, same seed) with accuracy (label P >= 0.5), Brier score, log score and a reliability
diagram (10 bins; the 95 % band of each bin's observed frequency is the Poisson-binomial of its
predicted P's). w_m: the catalogue's member counts (`--mixture`) or its most frequent member alone
(default: the body the product ships).

The product (--write-catalogue): per specimen one item, its most frequent member's body with
  input_gain: {lognormal: [exp(-mu), beta], nominal: exp(-mu)}  and  ensemble_size: N
which the node (ItemEnsemble) and rocking_experiments run as N Latin-hypercube members: the fraction
that overturns is the fitted P to within the 1/N strata.

  fragility_experiments.py --granite DIR --experiments BIN --catalogue CAT --cache-dir DIR --out-dir DIR
      [--baseline CALIB_OUT] [--write-catalogue FILE] [--plot FILE.png]
Stdlib, numpy, scipy (matplotlib for --plot).
"""
import argparse
import csv
import json
import math
import os
import shlex
import subprocess
import sys
import time

import numpy as np
from scipy import optimize, special

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from calibrate_experiments import (CalibrationError, data_digest, digest, scores, sha256_file,  # noqa: E402
                                   stratified_folds, write_atomic)
from progress_bar import add_quiet_flag, progress_bar  # noqa: E402

P_CLIP = 1e-3  # log score: probabilities clipped to [P_CLIP, 1 - P_CLIP] (a certain miss would be infinite)
BETA_MIN, BETA_MAX = 0.01, 5.0


# ================================================================ the fit (pure functions)

def grid_scales(lo, hi, n):
    """The margin search's grid (rocking_experiments --margins): lo (hi/lo)^(k/(n-1))."""
    return [hi if k == n - 1 else lo * (hi / lo) ** (k / (n - 1)) for k in range(n)]


def overturn_segments(pattern, grid, bracket_lo, bracket_hi):
    """Where in ln s the model overturns, from the runs made: the grid's outcomes (pattern) and the
    bisection's last bracket (stood at bracket_lo, overturned at bracket_hi); between two runs the
    outcome changes half-way in ln s. Returns [(a, b)] intervals of ln s (a may be -inf, b +inf)."""
    pts = {math.log(g): c == "1" for g, c in zip(grid, pattern)}
    if 0 < bracket_lo < bracket_hi:
        pts[math.log(bracket_lo)] = False
        pts[math.log(bracket_hi)] = True
    xs = sorted(pts)
    segs = []
    for i, x in enumerate(xs):
        if pts[x]:
            a = -math.inf if i == 0 else 0.5 * (xs[i - 1] + x)
            b = math.inf if i == len(xs) - 1 else 0.5 * (x + xs[i + 1])
            if segs and segs[-1][1] == a:
                segs[-1] = (segs[-1][0], b)
            else:
                segs.append((a, b))
    return segs


class Segments:
    """Every member's overturn intervals of every test, flat: a, b (ln s), test index, member index."""

    def __init__(self, per_member, n_tests):
        """per_member[m][i]: the segments of member m in test i."""
        rows = [(a, b, i, m) for m, tests in enumerate(per_member) for i, segs in enumerate(tests) for a, b in segs]
        arr = np.array(rows, dtype=float).reshape(-1, 4)
        self.a, self.b = arr[:, 0], arr[:, 1]
        self.test, self.member = arr[:, 2].astype(int), arr[:, 3].astype(int)
        self.n, self.members = n_tests, len(per_member)

    def subset(self, idx):
        """The tests idx (in that order) as a new Segments."""
        where = -np.ones(self.n, dtype=int)
        where[np.asarray(idx)] = np.arange(len(idx))
        keep = where[self.test] >= 0
        out = Segments.__new__(Segments)
        out.a, out.b, out.member = self.a[keep], self.b[keep], self.member[keep]
        out.test, out.n, out.members = where[self.test[keep]], len(idx), self.members
        return out


def fragility_p(seg, w, mu, beta):
    """P(overturn) per test: the real rock does what the model does at the scale exp(eps), eps ~ N(-mu,
    beta): the probability that eps falls where the model overturns, weighted over members (w sums to 1).
    For a test monotone in s that is Phi(-(ln s* + mu) / beta), s* its margin."""
    mass = special.ndtr((seg.b + mu) / beta) - special.ndtr((seg.a + mu) / beta)
    return np.bincount(seg.test, weights=np.asarray(w, dtype=float)[seg.member] * mass, minlength=seg.n)


def nll(seg, w, y, mu, beta):
    p = np.clip(fragility_p(seg, w, mu, beta), 1e-12, 1 - 1e-12)
    return -float(np.sum(y * np.log(p) + (1 - y) * np.log1p(-p)))


def fit_fragility(seg, w, y, fix_mu=None):
    """Maximum-likelihood (mu, beta) on these tests; beta in [BETA_MIN, BETA_MAX]. With fix_mu, beta alone.
    Deterministic: a coarse grid, then Nelder-Mead from its best point."""
    y = np.asarray(y, dtype=float)
    betas = np.exp(np.linspace(math.log(BETA_MIN), math.log(BETA_MAX), 40))
    mus = [fix_mu] if fix_mu is not None else np.linspace(-1.5, 1.5, 61)
    best = min((nll(seg, w, y, m, b), m, b) for m in mus for b in betas)
    lb = lambda v: min(max(v, math.log(BETA_MIN)), math.log(BETA_MAX))  # noqa: E731
    if fix_mu is None:
        r = optimize.minimize(lambda x: nll(seg, w, y, x[0], math.exp(lb(x[1]))), [best[1], math.log(best[2])],
                              method="Nelder-Mead", options={"xatol": 1e-6, "fatol": 1e-9, "maxiter": 4000})
        mu, beta = float(r.x[0]), math.exp(lb(r.x[1]))
    else:
        r = optimize.minimize_scalar(lambda v: nll(seg, w, y, fix_mu, math.exp(lb(v))),
                                     bounds=(math.log(BETA_MIN), math.log(BETA_MAX)), method="bounded")
        mu, beta = float(fix_mu), math.exp(lb(r.x))
    return {"mu": mu, "beta": beta, "nll": nll(seg, w, y, mu, beta)}


def cross_validate(seg, w, y, folds, fix_mu=None):
    """Held-out P per test (each fold from the fit on the others only) and the per-fold fits."""
    p = np.empty(len(y))
    fits = []
    for f in np.unique(folds):
        held = np.flatnonzero(folds == f)
        train = np.flatnonzero(folds != f)
        r = fit_fragility(seg.subset(train), w, y[train], fix_mu)
        p[held] = fragility_p(seg.subset(held), w, r["mu"], r["beta"])
        fits.append({"fold": int(f), "mu": r["mu"], "beta": r["beta"]})
    return p, fits


def log_score(p, y):
    """Mean -ln P(observed outcome), P clipped to [P_CLIP, 1 - P_CLIP]; lower is better."""
    p = np.clip(np.asarray(p, dtype=float), P_CLIP, 1 - P_CLIP)
    return float(-np.mean(y * np.log(p) + (1 - y) * np.log1p(-p)))


def poisson_binomial_band(p, level=0.95):
    """The central `level` interval of the count of successes of independent Bernoulli(p_i) (exact)."""
    dist = np.array([1.0])
    for q in p:
        dist = np.convolve(dist, [1 - q, q])
    c = np.cumsum(dist)
    a = (1 - level) / 2
    return int(np.searchsorted(c, a - 1e-12)), int(np.searchsorted(c, 1 - a - 1e-12))


def reliability(p, y, bins=10, min_tests=10):
    """Per bin of predicted P: tests, mean P, observed frequency and its 95 % band given the P's;
    'inside' for bins with at least min_tests tests."""
    p, y = np.asarray(p, dtype=float), np.asarray(y)
    b = np.minimum((p * bins).astype(int), bins - 1)
    out = []
    for k in range(bins):
        sel = b == k
        n = int(sel.sum())
        if n == 0:
            continue
        lo, hi = poisson_binomial_band(p[sel])
        k_obs = int(y[sel].sum())
        out.append({"bin": [k / bins, (k + 1) / bins], "tests": n, "mean_p": float(p[sel].mean()),
                    "observed": k_obs / n, "band": [lo / n, hi / n],
                    "inside": (lo <= k_obs <= hi) if n >= min_tests else None})
    return out


def all_scores(p, y):
    s = scores(p, y)
    s["log_score"] = log_score(p, y)
    s["reliability"] = reliability(p, y)
    judged = [r for r in s["reliability"] if r["inside"] is not None]
    s["bins_judged"], s["bins_inside"] = len(judged), sum(bool(r["inside"]) for r in judged)
    return s


# ================================================================ the catalogue and the margins

def catalogue_members(path):
    """{specimen: [(body text, count)]}, most frequent first: the items' YAML blocks without their id
    line, comments, input_gain and ensemble_size, identical bodies counted once."""
    try:
        with open(path) as fh:
            text = fh.read()
    except OSError as e:
        raise CalibrationError(f"--catalogue {path}: cannot read ({e})")
    if "items:" not in text:
        raise CalibrationError(f"--catalogue {path}: no 'items:' list")
    body = text.split("items:", 1)[1]
    out = {}
    for block in body.split("\n  - id:")[1:]:
        lines = block.split("\n")
        name = lines[0].strip().split("#")[0].strip()
        if not name:
            raise CalibrationError(f"--catalogue {path}: an item without an id (one '  - id: NAME' line per item)")
        keep = [ln for ln in lines[1:] if ln.strip() and not ln.strip().startswith("#")
                and ln.strip().split(":")[0] not in ("input_gain", "ensemble_size")]
        if any(not ln.startswith("    ") for ln in keep):
            raise CalibrationError(f"--catalogue {path}: item {name}: expected block items indented by 4 spaces")
        key = "\n".join(keep) + "\n"
        members = out.setdefault(name, {})
        members[key] = members.get(key, 0) + 1
    if not out:
        raise CalibrationError(f"--catalogue {path}: no items")
    return {n: sorted(m.items(), key=lambda kv: -kv[1]) for n, m in out.items()}


def run_margins(a, name, body, bhash, dhash):
    """rocking_experiments --margins on one member (a one-item catalogue), cached; returns the rows."""
    search = ["--margin-range", repr(a.margin_range[0]), repr(a.margin_range[1]), "--margin-grid", str(a.margin_grid),
              "--margin-bisections", str(a.margin_bisections)] + shlex.split(a.experiments_args)
    key = digest({"binary": bhash, "data": os.path.abspath(a.granite), "data_hash": dhash, "specimen": name,
                  "body": body, "args": search, "max_tests": a.max_tests})
    d = os.path.join(a.cache_dir, "margins")
    os.makedirs(d, exist_ok=True)
    cat, out = os.path.join(d, f"{name}_{key}.yaml"), os.path.join(d, f"{name}_{key}.csv")
    cached = os.path.exists(out)
    if not cached:
        write_atomic(cat, f"items:\n  - id: {name}\n{body}")
        cmd = [a.experiments, a.granite, "--catalogue", cat, "--margins", out + ".part"] + search
        if a.max_tests:
            cmd += ["--max-tests", str(a.max_tests)]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise CalibrationError(f"{' '.join(shlex.quote(c) for c in cmd)}: exit {r.returncode}: "
                                   f"{(r.stderr or r.stdout).strip()}")
        write_atomic(out + ".log", " ".join(shlex.quote(c) for c in cmd) + "\n" + r.stdout)
        os.replace(out + ".part", out)
    rows = []
    with open(out, newline="") as fh:
        for line, row in enumerate(csv.DictReader(fh), 2):
            try:
                rows.append({"test": int(row["test"]), "y": int(row["measured_overturned"]) if row["measured_overturned"] else -1,
                             "s": float(row["margin_scale"]), "censored": int(row["censored"]),
                             "chaotic": int(row["chaotic"]), "pattern": row["grid_outcomes"],
                             "bracket": (float(row["bracket_lo"]), float(row["bracket_hi"]))})
            except (KeyError, ValueError) as e:
                raise CalibrationError(f"{out}:{line}: bad margin row ({e})")
    return rows, cached


# ================================================================ reporting

def fmt(x, d=3):
    return "-" if x is None else f"{x:.{d}f}"


def rel_text(rows):
    return "; ".join(f"[{r['bin'][0]:.1f},{r['bin'][1]:.1f}) n {r['tests']}: P {r['mean_p']:.2f}, obs {r['observed']:.2f} "
                     f"(band {r['band'][0]:.2f}-{r['band'][1]:.2f}){'' if r['inside'] is None else (' ok' if r['inside'] else ' OUT')}"
                     for r in rows)


def markdown(summary):
    lines = [f"Made by: {summary['command']}", "",
             "| specimen | predictor | accuracy | recall | Brier | log score | reliability bins (n >= 10) inside the band |",
             "|---|---|---|---|---|---|---|"]
    for name, s in summary["specimens"].items():
        for label, r in s["table"]:
            lines.append(f"| {name} | {label} | {fmt(r['accuracy'])} | {fmt(r['recall'])} | {fmt(r['brier'])} | "
                         f"{fmt(r['log_score'])} | {r['bins_inside']} of {r['bins_judged']} |")
    lines.append("")
    for name, s in summary["specimens"].items():
        lines.append(f"- {name}: members {s['members']}; mu {s['fit']['mu']:.4f}, beta {s['fit']['beta']:.4f} "
                     f"(all tests; folds: mu {s['fold_mu'][0]:.3f}..{s['fold_mu'][1]:.3f}, beta "
                     f"{s['fold_beta'][0]:.3f}..{s['fold_beta'][1]:.3f}); chaotic tests {s['chaotic']}, s* <= "
                     f"{summary['margin_range'][0]:g}: {s['censored_below']}, s* > {summary['margin_range'][1]:g}: "
                     f"{s['censored_above']}")
        lines.append(f"  - reliability, {summary['shipped']} CV: {rel_text(s['cv']['reliability'])}")
    lines.append(f"\nMargins: {summary['margin_runs']} member runs ({summary['margins_cached']} cached); "
                 f"wall time {summary['wall_s']:.0f} s")
    return "\n".join(lines) + "\n"


def plot(path, summary, preds):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = list(summary["specimens"])
    fig, axes = plt.subplots(1, len(names), figsize=(5.2 * len(names), 5), squeeze=False)
    for ax, name in zip(axes[0], names):
        ax.plot([0, 1], [0, 1], color="0.6", lw=1, ls="--", label="perfect reliability")
        for key, label, colour, dx in (("p_cv", "fragility, 10-fold CV", "C0", 0.0),
                                       ("p_baseline", "today's calibrated model, 10-fold CV", "C3", 0.012)):
            p = preds[name].get(key)
            if p is None:
                continue
            rows = reliability(p, preds[name]["y"])
            x = np.array([r["mean_p"] for r in rows]) + dx
            obs = np.array([r["observed"] for r in rows])
            # the band the observed frequency should fall in (given the bin's P's), and the observed point
            ax.vlines(x, [r["band"][0] for r in rows], [r["band"][1] for r in rows], color=colour, lw=1.5, alpha=0.45)
            ax.plot(x, obs, "o", color=colour, ms=4, label=label)
            for r, xx, oo in zip(rows, x, obs):
                ax.annotate(str(r["tests"]), (xx, oo), textcoords="offset points", xytext=(5, -10 if dx else 4),
                            fontsize=7, color=colour)
        s = summary["specimens"][name]
        ax.set_title(f"{name}: Brier {s['cv']['brier']:.3f}, accuracy {s['cv']['accuracy']:.3f} (fragility, CV)", fontsize=9)
        ax.set_xlabel("predicted P(overturn), mean in each bin of 0.1")
        ax.set_ylabel("observed frequency of overturn")
        ax.set_xlim(-0.03, 1.03)
        ax.set_ylim(-0.03, 1.03)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower right", title="points: observed; bars: 95 % band given the P's; numbers: tests", title_fontsize=6.5)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def write_catalogue(path, summary, bodies, members, command):
    head = ["# fragility_experiments: the granite specimens with a calibrated P(overturn) (issue 41; docs/validation.md",
            "# section 0). Each item: the calibrated body (the most frequent member of the --catalogue named below) and",
            "# a lognormal input_gain fitted by maximum likelihood on ALL tests (in-sample): the model at the",
            "# gain exp(eps) stands for the real rock, eps ~ N(-mu, beta), so P(overturn) = Phi(-(ln s* + mu) / beta),",
            "# s* the test's margin (the smallest overturning scale). The node and rocking_experiments run",
            "# ensemble_size Latin-hypercube members: P is the fraction that overturn (1/N strata).",
            f"# made by: {command}"]
    body = []
    for name, s in summary["specimens"].items():
        f = s["fit"]
        med = math.exp(-f["mu"])
        cv = s["cv"]
        body.append(f"  - id: {name}\n"
                    f"    # body: {s['members_note']}; mu {f['mu']:.4f}, beta {f['beta']:.4f}; 10-fold CV: accuracy "
                    f"{cv['accuracy']:.3f}, Brier {cv['brier']:.3f}, log score {cv['log_score']:.3f}\n" + bodies[name] +
                    f"    input_gain: {{lognormal: [{med:.6g}, {f['beta']:.6g}], nominal: {med:.6g}}}   # dimensionless: "
                    "scales the ground acceleration (median, beta = sd of its log)\n"
                    f"    ensemble_size: {members}   # members, Latin hypercube over input_gain\n")
    write_atomic(path, "\n".join(head) + "\nitems:\n" + "".join(body))


# ================================================================ main

def parser():
    """The command line (apart from main, which stays within a screen)."""
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--granite", required=True, metavar="DIR", help="the data set: tests/TestNNN.csv(.gz), outcomes.csv")
    ap.add_argument("--experiments", required=True, metavar="BIN", help="the rocking_experiments executable")
    ap.add_argument("--catalogue", required=True, help="calibrated catalogue (members NAME#k) or a fragility catalogue")
    ap.add_argument("--cache-dir", required=True)
    ap.add_argument("--out-dir", required=True)
    ap.add_argument("--baseline", metavar="DIR", help="calibrate_experiments.py --out-dir: its held-out P (p_cv) "
                    "scored beside on the same folds")
    ap.add_argument("--mixture", action="store_true", help="ship the members' mixture's fit in the summary's "
                    "'shipped' row (the catalogue can carry one body per specimen: the most frequent)")
    ap.add_argument("--folds", type=int, default=10)
    ap.add_argument("--seed", type=int, default=20, help="fold assignment seed (calibrate_experiments.py's default)")
    ap.add_argument("--margin-range", type=float, nargs=2, default=[0.25, 4.0], metavar=("LO", "HI"))
    ap.add_argument("--margin-grid", type=int, default=17, help="scales on the grid (17: steps of 2^(1/4); 9 misses more chaotic windows, docs/validation.md)")
    ap.add_argument("--margin-bisections", type=int, default=5)
    ap.add_argument("--experiments-args", default="", metavar="'ARGS'", help="more rocking_experiments arguments "
                    "(e.g. '--model 3d'), with '='")
    ap.add_argument("--max-tests", type=int, default=0, help="only the first N tests (trials)")
    ap.add_argument("--write-catalogue", metavar="FILE")
    ap.add_argument("--members", type=int, default=20, help="ensemble_size in --write-catalogue")
    ap.add_argument("--plot", metavar="PNG", help="reliability diagram")
    add_quiet_flag(ap)
    return ap


def check_inputs(a):
    if not (os.path.isfile(a.experiments) and os.access(a.experiments, os.X_OK)):
        raise CalibrationError(f"--experiments {a.experiments}: not an executable (build rocking_experiments)")
    if not os.path.isdir(os.path.join(a.granite, "tests")):
        raise CalibrationError(f"--granite {a.granite}: no tests/ directory")


def member_margins(a, name, members, bhash, dhash, summary, bar):
    """Every member body's margins of the specimen's tests (run_margins, cached)."""
    runs = []
    for body, count in members:
        rows, cached = run_margins(a, name, body, bhash, dhash)
        summary["margin_runs"] += 1
        summary["margins_cached"] += cached
        runs.append(rows)
        bar.update()
    return runs


def fit_specimen(a, name, members, runs, summary, preds, bodies, all_p):
    """The specimen's fragility: fit, cross-validation and the variants scored against it, into
    summary["specimens"][name]; its predictions in preds and all_p, its shipped body in bodies; its CSV."""
    tests = [r["test"] for r in runs[0]]
    if any([r["test"] for r in rr] != tests for rr in runs):
        raise CalibrationError(f"{name}: the members' margins cover different tests")
    keep = np.array([r["y"] >= 0 for r in runs[0]])
    y = np.array([r["y"] for r in runs[0]])[keep]
    ln_s = np.log(np.array([[r["s"] for r in rr] for rr in runs]))[:, keep]
    grid = grid_scales(a.margin_range[0], a.margin_range[1], a.margin_grid)
    for rr in runs:
        if any(len(r["pattern"]) != a.margin_grid for r in rr):
            raise CalibrationError(f"{name}: margins with another grid than --margin-grid {a.margin_grid}")
    seg = Segments([[overturn_segments(r["pattern"], grid, *r["bracket"]) for r, k in zip(rr, keep) if k]
                    for rr in runs], int(keep.sum()))
    # the margin alone (the first overturn; chaotic tests as if monotone above it)
    seg_first = Segments([[[(v, math.inf)] for v in row] for row in ln_s], int(keep.sum()))
    counts = np.array([c for _, c in members], dtype=float)
    w_mix = counts / counts.sum()
    w_top = np.zeros(len(members))
    w_top[0] = 1.0
    folds = stratified_folds(y, a.folds, a.seed)
    w_ship = w_mix if a.mixture else w_top
    p_cv, fits = cross_validate(seg, w_ship, y, folds)
    fit = fit_fragility(seg, w_ship, y)
    p_in = fragility_p(seg, w_ship, fit["mu"], fit["beta"])
    cvl = f"{a.folds}-fold CV"
    variants = [(f"fragility (mu, beta), {cvl}", p_cv)]
    other = w_top if a.mixture else w_mix
    if len(members) > 1:
        variants.append((f"fragility, {'most frequent member' if a.mixture else 'mixture of members'}, {cvl}",
                         cross_validate(seg, other, y, folds)[0]))
    variants.append((f"fragility, no bias (mu = 0), {cvl}", cross_validate(seg, w_ship, y, folds, fix_mu=0.0)[0]))
    variants.append((f"fragility on the first overturn s* alone, {cvl}", cross_validate(seg_first, w_ship, y, folds)[0]))
    variants.append(("fragility, in-sample", p_in))
    # the members' own 0/1 outcome at scale 1 (the calibrated catalogue as shipped, fitted on all tests)
    k1 = [i for i, g in enumerate(grid) if abs(g - 1.0) < 1e-9]
    if k1:
        at1 = np.array([[int(r["pattern"][k1[0]]) for r in rr] for rr in runs], dtype=float)[:, keep]
        variants.append(("calibrated members at scale 1 (0/1, in-sample posterior)", w_mix @ at1))
    p_base = None
    if a.baseline:
        p_base = read_baseline(a.baseline, name, np.array(tests)[keep], folds)
        variants.append((f"today's calibrated model, {cvl} (grid posterior)", p_base))
    table = [(label, all_scores(p, y)) for label, p in variants]
    chaotic = sum(r["chaotic"] for r in runs[0])
    summary["specimens"][name] = {
        "tests": int(len(y)), "overturned": int(y.sum()), "members": [c for _, c in members],
        "members_note": (f"the most frequent of {len(members)} distinct members ({members[0][1]} of "
                         f"{int(counts.sum())})" if len(members) > 1 else "the catalogue's one body"),
        "fit": fit, "fold_fits": fits, "fold_mu": [min(f["mu"] for f in fits), max(f["mu"] for f in fits)],
        "fold_beta": [min(f["beta"] for f in fits), max(f["beta"] for f in fits)],
        "cv": table[0][1], "table": table,
        "chaotic": chaotic, "chaotic_per_member": [sum(r["chaotic"] for r in rr) for rr in runs],
        "censored_below": sum(r["censored"] < 0 for r in runs[0]),
        "censored_above": sum(r["censored"] > 0 for r in runs[0])}
    preds[name] = {"y": y, "p_cv": p_cv, "p_baseline": p_base}
    all_p[name] = (y, p_cv, p_base)
    bodies[name] = members[0][0]
    write_specimen_csv(a, name, runs, tests, keep, y, folds, p_cv, p_in, ln_s)


def write_specimen_csv(a, name, runs, tests, keep, y, folds, p_cv, p_in, ln_s):
    """fragility_NAME.csv: per kept test its outcome, fold, P (held-out and in-sample) and margins."""
    os.makedirs(a.out_dir, exist_ok=True)
    with open(os.path.join(a.out_dir, f"fragility_{name}.csv"), "w") as fh:
        fh.write("test,measured,fold,p_cv,p_in_sample," + ",".join(f"s_star_member{m}" for m in range(len(runs))) +
                 ",chaotic_member0,grid_outcomes_member0\n")
        kept = [r for r, k in zip(runs[0], keep) if k]
        for j, t in enumerate(np.array(tests)[keep]):
            fh.write(f"{t},{y[j]},{folds[j]},{p_cv[j]:.6f},{p_in[j]:.6f}," +
                     ",".join(f"{math.exp(v):.6g}" for v in ln_s[:, j]) +
                     f",{kept[j]['chaotic']},{kept[j]['pattern']}\n")


def score_both_specimens(summary, all_p):
    """The specimens' held-out P scored together (and today's calibrated model's, with --baseline)."""
    if len(all_p) > 1:
        y = np.concatenate([v[0] for v in all_p.values()])
        both = all_scores(np.concatenate([v[1] for v in all_p.values()]), y)
        summary["both_cv"] = {k: both[k] for k in ("accuracy", "brier", "log_score", "bins_judged", "bins_inside")}
        if all(v[2] is not None for v in all_p.values()):
            bb = all_scores(np.concatenate([v[2] for v in all_p.values()]), y)
            summary["both_baseline_cv"] = {k: bb[k] for k in ("accuracy", "brier", "log_score")}


def write_summary(a, summary):
    """summary.json and summary.md in --out-dir; the markdown also to stdout."""
    os.makedirs(a.out_dir, exist_ok=True)
    md = markdown(summary)
    if "both_cv" in summary:
        b = summary["both_cv"]
        md += (f"\nBoth specimens, fragility 10-fold CV: accuracy {b['accuracy']:.3f}, Brier {b['brier']:.3f}, "
               f"log score {b['log_score']:.3f}")
        if "both_baseline_cv" in summary:
            c = summary["both_baseline_cv"]
            md += f"; today's: {c['accuracy']:.3f}, {c['brier']:.3f}, {c['log_score']:.3f}"
        md += "\n"
    with open(os.path.join(a.out_dir, "summary.json"), "w") as fh:
        json.dump(summary, fh, indent=1, default=lambda o: o.tolist() if hasattr(o, "tolist") else str(o))
    with open(os.path.join(a.out_dir, "summary.md"), "w") as fh:
        fh.write(md)
    sys.stdout.write(md)


def run_fragility(a, command):
    """Margins, fits and scores per specimen, the summary, and --plot / --write-catalogue (module docstring)."""
    t0 = time.time()
    try:
        check_inputs(a)
        specimens = catalogue_members(a.catalogue)
        bhash, dhash = sha256_file(a.experiments), data_digest(a.granite)
        summary = {"command": command, "folds": a.folds, "seed": a.seed, "margin_range": a.margin_range,
                   "p_clip_log_score": P_CLIP, "specimens": {}, "margin_runs": 0, "margins_cached": 0,
                   "shipped": "mixture" if a.mixture else "most frequent member"}
        preds, bodies, all_p = {}, {}, {}
        bar = progress_bar(sum(len(m) for m in specimens.values()), "fragility_experiments: members", a.quiet)
        for name, members in specimens.items():
            runs = member_margins(a, name, members, bhash, dhash, summary, bar)
            fit_specimen(a, name, members, runs, summary, preds, bodies, all_p)
        bar.close()  # the last member is done: the summary below is not drawn over
        score_both_specimens(summary, all_p)
        summary["wall_s"] = time.time() - t0
        write_summary(a, summary)
        if a.plot:
            plot(a.plot, summary, preds)
        if a.write_catalogue:
            write_catalogue(a.write_catalogue, summary, bodies, a.members, command)
            print(f"fragility_experiments: catalogue written to {a.write_catalogue}", file=sys.stderr)
    except CalibrationError as e:
        print(f"fragility_experiments: error: {e}", file=sys.stderr)
        return 2
    return 0


def main(argv=None):
    a = parser().parse_args(argv)
    command = " ".join(["fragility_experiments.py"] + [shlex.quote(x) for x in (sys.argv[1:] if argv is None else argv)])
    return run_fragility(a, command)


def read_baseline(d, name, tests, folds):
    """calibrate_experiments.py's held-out P of these tests; its folds must be these folds."""
    path = os.path.join(d, f"predictions_{name}.csv")
    try:
        with open(path, newline="") as fh:
            rows = {int(r["test"]): (float(r["p_cv"]), int(r["fold"])) for r in csv.DictReader(fh)}
    except (OSError, KeyError, ValueError) as e:
        raise CalibrationError(f"--baseline {path}: cannot read test, p_cv, fold ({e})")
    missing = [t for t in tests if t not in rows]
    if missing:
        raise CalibrationError(f"--baseline {path}: no row for test(s) {missing[:5]}")
    if any(rows[t][1] != f for t, f in zip(tests, folds)):
        raise CalibrationError(f"--baseline {path}: its folds differ from these (same --folds and --seed?)")
    return np.array([rows[t][0] for t in tests])


if __name__ == "__main__":
    sys.exit(main())
