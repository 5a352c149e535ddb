"""plot_performance_stability: the stability-map charts of docs/performance.md (issue 42 split them
out of plot_performance.py, which calls plot_stability on rocking_accuracy stability's CSV).

stability_summary.* (the failing kinds per cell, every method), stability_rk4.*, stability_dopri5.*,
stability_analytic.* (each failure kind's severity per cell) and the summary's failing-cells table.
"""
import math
from collections import defaultdict

from matplotlib.colors import LogNorm, ListedColormap, BoundaryNorm

from plot_performance_common import fnum, plt, save


# ----------------------------------------------------------------------------- stability maps
FAILURES = [
    ("M", "missed impacts",
     "impacts short of the reference by > 2 % (free rocking until rest), or first-10 impact times off by > 0.05/p s"),
    ("C", "spurious chattering",
     "more impacts than the reference by > 2 %, or a forced rest capture"),
    ("E", "energy gained",
     "a free-rocking peak higher than the one before it (> 1e-6 relative), or a spurious overturn"),
    ("D", "wrong overturn decisions",
     "overturning amplitude of one-sine pulses (wp = 2p, 4p) shifted by > 0.1 % from the reference's"),
    ("R", "rest capture misfiring",
     "returns to rest more than 2 samples + 0.5 % away from the reference, or never / when it should not"),
]


def failures(r):
    imp, ref = fnum(r["impacts"]), fnum(r["ref_impacts"])
    tol = max(1.0, 0.02 * ref)
    p = fnum(r["p"])
    dt = 1.0 / fnum(r["feed_hz"])
    e_imp = fnum(r["err_impact_s"])
    out = {}
    out["M"] = (ref - imp > tol) or (not math.isnan(e_imp) and p * e_imp > 0.05)
    out["C"] = (imp - ref > tol) or fnum(r["forced_rest"]) > 0
    out["E"] = (fnum(r["energy_gain"]) > 1e-6 and fnum(r["ref_energy_gain"]) <= 1e-6) or r["free_overturned"] == "1"
    shift = fnum(r["boundary_shift"])
    out["D"] = not math.isnan(shift) and shift > 1e-3
    rt, rr = fnum(r["rest_time"]), fnum(r["ref_rest_time"])
    if math.isnan(rt) and math.isnan(rr):
        out["R"] = False
    elif math.isnan(rt) != math.isnan(rr):
        out["R"] = True
    else:
        out["R"] = abs(rt - rr) > 2 * dt + 0.005 * rr
    return out


def metric_values(r):
    """Continuous severity of each failure kind (for the detailed maps)."""
    imp, ref = fnum(r["impacts"]), fnum(r["ref_impacts"])
    p = fnum(r["p"])
    e_imp = fnum(r["err_impact_s"])
    rt, rr = fnum(r["rest_time"]), fnum(r["ref_rest_time"])
    dt = 1.0 / fnum(r["feed_hz"])
    rest = float("inf") if math.isnan(rt) != math.isnan(rr) else (0.0 if math.isnan(rt) else abs(rt - rr) / dt)
    return {
        "M": max(p * e_imp if not math.isnan(e_imp) else 0.0, max(0.0, (ref - imp) / max(ref, 1))),
        "C": max(0.0, (imp - ref) / max(ref, 1)) + (1.0 if fnum(r["forced_rest"]) > 0 else 0.0),
        "E": 1.0 if r["free_overturned"] == "1" else fnum(r["energy_gain"]),
        "D": fnum(r["boundary_shift"]),
        "R": rest,
    }


METRIC_LABELS = {
    "M": "p x impact-time error (rad), or share of impacts missed",
    "C": "share of extra impacts",
    "E": "largest relative rise of a free-rocking peak",
    "D": "relative shift of the overturning amplitude",
    "R": "|rest time - reference| in samples",
}
METRIC_THRESHOLDS = {"M": 0.05, "C": 0.02, "E": 1e-6, "D": 1e-3, "R": 2.0}


def grid_of(rows, xkey, ykey="p"):
    xs = sorted({fnum(r[xkey]) for r in rows})
    ys = sorted({fnum(r[ykey]) for r in rows})
    return xs, ys


def draw_summary_panel(ax, rows, xkey, xlabel, title, xlog=True, xreverse=False):
    xs, ys = grid_of(rows, xkey)
    cmap = ListedColormap(["#e8f5e9", "#ffe082", "#ffab91", "#e57373", "#b71c1c", "#4a0000"])
    norm = BoundaryNorm([-0.5, 0.5, 1.5, 2.5, 3.5, 4.5, 5.5], cmap.N)
    z = [[float("nan")] * len(xs) for _ in ys]
    text = {}
    for r in rows:
        i, j = ys.index(fnum(r["p"])), xs.index(fnum(r[xkey]))
        f = failures(r)
        letters = "".join(k for k in "MCEDR" if f[k])
        z[i][j] = len(letters)
        text[(i, j)] = letters
    ax.imshow(z, origin="lower", aspect="auto", cmap=cmap, norm=norm,
              extent=(-0.5, len(xs) - 0.5, -0.5, len(ys) - 0.5))
    for (i, j), t in text.items():
        if t:
            ax.text(j, i, t, ha="center", va="center", fontsize=6.5, color="k" if len(t) < 3 else "w")
    ax.set_xticks(range(len(xs)))
    if xkey == "param" and rows and rows[0]["method"] == "dopri5":
        ax.set_xticklabels([f"1e{int(round(math.log10(x)))}" for x in xs], fontsize=7)
    elif xkey == "h":
        ax.set_xticklabels([f"{1000 * x:.3g}" for x in xs], fontsize=7, rotation=45)
    else:
        ax.set_xticklabels([f"{x:g}" for x in xs], fontsize=7)
    ax.set_yticks(range(len(ys)))
    ax.set_yticklabels([f"{y:g}" for y in ys], fontsize=7)
    ax.set_xlabel(xlabel, fontsize=8)
    ax.set_ylabel("p (rad/s)", fontsize=8)
    ax.set_title(title, fontsize=9)
    if xreverse:
        ax.invert_xaxis()


def plot_stability(directory, rows, summary):
    rk = [r for r in rows if r["method"] == "rk4" and r["model"] == "nonlinear"]
    dp = [r for r in rows if r["method"] == "dopri5"]
    an = [r for r in rows if r["method"] == "analytic"]
    alphas = sorted({fnum(r["alpha_deg"]) for r in rk})

    plot_failing_kinds(directory, rk, dp, an, alphas)
    plot_severity_maps(directory, rk, dp, an, alphas)
    summarise_failing_cells(rows, summary)


def plot_failing_kinds(directory, rk, dp, an, alphas):
    """stability_summary: the letters of the failing kinds in every cell, every method."""
    panels = []
    for a in alphas:
        panels.append(("rk4", [r for r in rk if fnum(r["alpha_deg"]) == a], "h",
                       "step h = input interval / sub-steps (ms)", f"rk4, alpha = {a:g} deg"))
    for feed in (200, 20):
        for a in alphas:
            sub = [r for r in dp if fnum(r["alpha_deg"]) == a and fnum(r["feed_hz"]) == feed]
            if sub:
                panels.append(("dopri5", sub, "param", "tolerance", f"dopri5 at {feed} Hz, alpha = {a:g} deg"))
    if an:
        panels.append(("analytic", an, "alpha_deg", "alpha (deg)", "analytic (linearized) vs nonlinear, 200 Hz"))
    ncol = 4
    nrow = math.ceil(len(panels) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.3 * ncol, 3.9 * nrow + 1.0), squeeze=False)
    for k, (method, sub, xkey, xlabel, title) in enumerate(panels):
        ax = axes[k // ncol][k % ncol]
        draw_summary_panel(ax, sub, xkey, xlabel, title, xreverse=(method == "dopri5"))
    for k in range(len(panels), nrow * ncol):
        axes[k // ncol][k % ncol].set_visible(False)
    legend = "   ".join(f"{c} = {name}" for c, name, _ in FAILURES)
    fig.suptitle("Where each method fails (nonlinear reference: dopri5 tol 1e-12 on 8x finer samples)\n"
                 + legend + "   (green: none)", fontsize=10)
    fig.tight_layout()
    save(fig, directory, "stability_summary")


def plot_severity_maps(directory, rk, dp, an, alphas):
    """stability_rk4, stability_dopri5, stability_analytic (those with rows)."""
    if rk:
        plot_severity_map(directory, "rk4",
                          [(f"rk4, alpha = {a:g} deg", [r for r in rk if fnum(r["alpha_deg"]) == a]) for a in alphas],
                          "h", lambda x: f"{1000 * x:.3g}")
    if dp:
        sets = []
        for feed in (200, 20):
            for a in alphas:
                sub = [r for r in dp if fnum(r["alpha_deg"]) == a and fnum(r["feed_hz"]) == feed]
                if sub:
                    sets.append((f"dopri5 {feed} Hz, alpha = {a:g} deg", sub))
        plot_severity_map(directory, "dopri5", sets, "param", lambda x: f"1e{int(round(math.log10(x)))}")
    if an:
        plot_severity_map(directory, "analytic", [("analytic (linearized) vs nonlinear", an)], "alpha_deg",
                          lambda x: f"{x:g}")


def plot_severity_map(directory, name, sets, xkey, xfmt):
    """stability_NAME: one column per set, one row per failure kind (its severity; x where it fails)."""
    fig, axes = plt.subplots(len(FAILURES), len(sets), figsize=(3.6 * len(sets), 2.7 * len(FAILURES) + 0.8),
                             squeeze=False)
    for col, (title, sub) in enumerate(sets):
        xs, ys = grid_of(sub, xkey)
        for row, (code, fname, _desc) in enumerate(FAILURES):
            ax = axes[row][col]
            z = [[float("nan")] * len(xs) for _ in ys]
            fail = []
            for r in sub:
                i, j = ys.index(fnum(r["p"])), xs.index(fnum(r[xkey]))
                v = metric_values(r)[code]
                z[i][j] = min(max(v, 1e-12), 1e3) if not math.isnan(v) else float("nan")
                if failures(r)[code]:
                    fail.append((j, i))
            im = ax.imshow(z, origin="lower", aspect="auto", cmap="viridis",
                           norm=LogNorm(vmin=1e-10, vmax=1e2),
                           extent=(-0.5, len(xs) - 0.5, -0.5, len(ys) - 0.5))
            for j, i in fail:
                ax.text(j, i, "x", ha="center", va="center", color="red", fontsize=9, fontweight="bold")
            ax.set_xticks(range(len(xs)))
            ax.set_xticklabels([xfmt(x) for x in xs], fontsize=6, rotation=45)
            ax.set_yticks(range(len(ys)))
            ax.set_yticklabels([f"{y:g}" for y in ys], fontsize=6)
            if row == 0:
                ax.set_title(title, fontsize=8.5)
            if col == 0:
                ax.set_ylabel(f"{fname}\np (rad/s)", fontsize=8)
            if row == len(FAILURES) - 1:
                ax.set_xlabel({"h": "step h (ms)", "param": "tolerance", "alpha_deg": "alpha (deg)"}[xkey],
                              fontsize=8)
            if xkey == "param":
                ax.invert_xaxis()
            if col == len(sets) - 1:
                cb = fig.colorbar(im, ax=ax, fraction=0.05)
                cb.ax.tick_params(labelsize=6.5)
                cb.set_label(METRIC_LABELS[code] + f"\n(x: > {METRIC_THRESHOLDS[code]:g})", fontsize=7)
    fig.suptitle(f"{name}: severity of each failure kind (colour) and failing cells (red x)", fontsize=10)
    fig.tight_layout()
    save(fig, directory, f"stability_{name}")


def summarise_failing_cells(rows, summary):
    """The summary's lines: the failing cells of each method."""
    summary.append("## Stability maps: failing cells\n")
    summary.append("Failure kinds: " + "; ".join(f"**{c}** {n}: {d}" for c, n, d in FAILURES) + ".\n")
    summary.append("| method | input rate | alpha | failing cells (of) | kinds seen | smallest p*h with a failure |")
    summary.append("|---|---|---|---|---|---|")
    groups = defaultdict(list)
    for r in rows:
        groups[(r["method"], r["feed_hz"] if r["method"] != "rk4" else "all", r["alpha_deg"] if r["method"] != "analytic" else "all")].append(r)
    for (m, feed, a), rs in sorted(groups.items()):
        bad = [r for r in rs if any(failures(r).values())]
        kinds = sorted({k for r in bad for k, v in failures(r).items() if v})
        ph = min((fnum(r["p_h"]) for r in bad), default=float("nan"))
        summary.append(f"| {m} | {feed} | {a} | {len(bad)} ({len(rs)}) | {''.join(kinds)} | {ph:.3g} |")
    summary.append("")
