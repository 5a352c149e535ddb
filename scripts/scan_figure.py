"""scan_figure: one picture of what rocking_catalogue from-scan made of a scan (issue 43): the scan as
stood on its floor (removed floor or turntable in grey, the cap over the open base in blue), its base
(contact points, base polygon, centre of mass, the pivots of both planes), and what the monitor
derives from the entry (catalogue_check's numbers)."""
import math
import textwrap

import numpy as np

G = 9.80665


def plot_scan(path, item_id, g, derived, notes):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    mesh = g["_mesh"]
    v, f, caps = mesh["vertices"], mesh["faces"], mesh["caps"]
    fig = plt.figure(figsize=(15, 5.4))
    draw_stood_scan(fig, item_id, g, mesh, v, f, caps)
    draw_base(fig, g, v)
    draw_derived_table(fig, derived, notes)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def draw_stood_scan(fig, item_id, g, mesh, v, f, caps):
    """Left: the scan stood on its floor, shaded, with the removed floor, the cap and the centre of mass."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    ax = fig.add_subplot(1, 3, 1, projection="3d")
    step = max(1, (len(f) - caps) // 15000)  # a picture, not the mesh: at most ~15k triangles drawn
    body = f[: len(f) - caps][::step]
    tri = v[body]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1), 1e-300)[:, None]
    light = 0.45 + 0.55 * np.clip(n @ np.array([0.4, -0.5, 0.77]), 0, 1)  # Lambert, light from above
    ax.add_collection3d(Poly3DCollection(tri, facecolors=light[:, None] * np.array([0.82, 0.71, 0.55]),
                                         edgecolor="none"))
    if caps:
        ax.add_collection3d(Poly3DCollection(v[f[len(f) - caps:]], facecolor="tab:blue", alpha=0.6))
    rem = mesh["removed"]
    if len(rem):
        ax.add_collection3d(Poly3DCollection(rem[:: max(1, len(rem) // 5000)], facecolor="0.7", alpha=0.35))
    pts = np.vstack([v] + ([rem.reshape(-1, 3)] if len(rem) else []))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    c, r = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(max(lo[2], c[2] - r), max(lo[2], c[2] - r) + 2 * r)
    com = g["com"]
    ax.scatter([com[0]], [com[1]], [com[2]], c="k", marker="*", s=80)
    ax.set_xlabel("x, m")
    ax.set_ylabel("y, m")
    ax.set_zlabel("z, m")
    ax.set_title(f"{item_id}: the scan stood on its floor\n(grey: removed turntable/floor; blue: cap; *: centre of mass)",
                 fontsize=9)


def draw_base(fig, g, v):
    """Middle: the base seen from above: contact points, base polygon, centre of mass, both planes' pivots."""
    com = g["com"]
    ax2 = fig.add_subplot(1, 3, 2)
    low = v[v[:, 2] <= g["contact_tolerance"]]
    ax2.scatter(low[:, 0], low[:, 1], s=2, c="0.6", label=f"contact points (within {g['contact_tolerance'] * 1000:g} mm)")
    poly = np.array(g["base_polygon"] + g["base_polygon"][:1])
    ax2.plot(poly[:, 0], poly[:, 1], "g-", lw=1.5, label="base_polygon")
    ax2.plot(com[0], com[1], "k*", ms=12, label="centre of mass")
    for plane, col in (("x", "tab:red"), ("y", "tab:blue")):
        for k, piv in enumerate(g[plane]["pivots"], 1):
            p = piv["point"]
            ax2.plot(p[0], p[1], "o", color=col, ms=6,
                     label=f"{plane}-plane pivots" if k == 1 else None)
    ax2.set_aspect("equal")
    ax2.set_xlabel("x, m (floor frame)")
    ax2.set_ylabel("y, m")
    ax2.set_title("its base, seen from above", fontsize=9)
    ax2.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)


def draw_derived_table(fig, derived, notes):
    """Right: catalogue_check's numbers per plane, and the scan's notes."""
    ax3 = fig.add_subplot(1, 3, 3)
    ax3.axis("off")
    rows = [["", "x plane", "y plane"]]
    planes = {p["plane"]: p for p in derived["planes"]}

    def line(label, fn):
        rows.append([label] + [fn(planes[k]) if k in planes else "-" for k in ("x", "y")])

    line("base B, m", lambda p: f"{p['width']:.3f}")
    line("centre of mass h, m", lambda p: f"{p['cg_height']:.3f}")
    line("alpha 1 / 2, deg", lambda p: " / ".join(f"{math.degrees(q['alpha']):.2f}" for q in p["pivots"]))
    weak = lambda p: min(p["pivots"], key=lambda q: q["alpha"])  # noqa: E731
    line("R (weaker corner), m", lambda p: f"{weak(p)['radius']:.3f}")
    line("p, rad/s", lambda p: f"{weak(p)['p']:.3f}")
    line("eta (eq. 34)", lambda p: f"{weak(p)['eta']:.3f}")
    line("uplift from rest", lambda p: f"{weak(p)['uplift_acceleration'] / G:.3f} g")
    line("Housner PSV (eq. 1), m/s", lambda p: f"{p['housner_pseudo_velocity']:.3f}")
    line("Ishiyama PGV, m/s", lambda p: f"{p['ishiyama_velocity']:.3f}")
    line("Ishiyama PGA, m/s^2", lambda p: f"{p['ishiyama_acceleration']:.2f}")
    line("mu_s", lambda p: "-" if p["mu_s"] is None else f"{p['mu_s']:.2f}")
    line("slides before it rocks", lambda p: {None: "no mu_s", True: "yes", False: "no"}[p["slides_first"]])
    table = ax3.table(cellText=rows, loc="upper center", cellLoc="left", colWidths=[0.5, 0.25, 0.25])
    table.auto_set_font_size(False)
    table.set_fontsize(8)
    table.scale(1, 1.35)
    ax3.set_title("what the monitor derives (catalogue_check)", fontsize=9)
    text = "\n".join(textwrap.fill(n, 100, subsequent_indent="  ") for n in notes)
    ax3.text(0.0, 0.02, text, fontsize=6, va="bottom", family="monospace", transform=ax3.transAxes)
