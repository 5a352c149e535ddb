#!/usr/bin/env python3
"""rocking_geometry: a rocking item's catalogue entry from a mesh or a scan (issues 20, 43).

Reads PLY, STL, OBJ, OFF, glTF or GLB (.gz allowed; meshio and assimp, mesh_input.py); a MESH is a
scan: unit, floor or turntable, holes, floor face and bad meshes handled as scan_entry.py states
(docs/own_objects.md). Places it, and computes exactly (signed tetrahedra, homogeneous density):
  - volume, centre of mass, central inertia tensor;
  - the base contact: the vertices within --contact-tolerance of the lowest one, and their convex
    hull on the floor;
  - for the shaking axis (world x) the two pivots (the hull's extreme points along x), the height of
    the centre of mass above the floor, per pivot alpha, R and the inertia about the pivot (parallel
    axis, about the horizontal axis perpendicular to the shaking);
  - the same across it (world y): the catalogue's second plane;
  - the catalogue entry (width, cg_height, eccentricity, radius_of_gyration; depth, eccentricity_y,
    radius_of_gyration_y) that the monitor, rocking_sim and rocking_experiments read;
  - the 3-D description in the same entry (mass, centre_of_mass, base_polygon, central_inertia), in
    the floor frame of the placed body: z up, z = 0 the floor (the lowest vertex), x the shaking axis
    (world x), y = z cross x (world y); base_polygon is the contact's convex hull, counter-clockwise
    seen from above, without duplicate or (within 1 um) collinear vertices.

The planar model (docs/validation.md) assumes both pivots on one flat floor: the entry uses the
height of the centre of mass above the lowest vertex; the pivots' own heights (within the tolerance)
are reported, with the exact per-pivot alpha they would give.

  rocking_geometry.py MESH [--mass KG] [--com X Y Z] [--unit U] [--up AXIS] [--floor F] [--no-hull] ...
  rocking_geometry.py --granite DIR [--yaml OUT] [--plot-dir DIR]   (the two granite specimens)
  ... [--com-shift DX DY]: the centre of mass moved horizontally after placement (calibration)
  ... [--planar-only]: without the 3-D keys (for a catalogue reader that does not know them yet)
"""
import argparse
import json
import math
import os
import sys

import numpy as np

# the modules beside this file, also when run through catkin's devel-space relay (which execs it from
# build/devel/lib, where they are not)
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from mesh_input import GeometryError  # noqa: E402  (beside this script)
# the mesh math and the placed body's quantities, in rocking_geometry_solid so that scan_entry.py can
# use them without importing this module back (re-exported: rg.mass_properties, rg.rocking_geometry,
# rg.fmt, ... are used by callers and tests)
from rocking_geometry_solid import (  # noqa: E402,F401
    MAX_BASE_VERTICES, MAX_HULL_VERTICES, POLYGON_TOLERANCE, base_polygon, central_inertia, contact_hull,
    convex_hull_2d, fmt, mass_properties, open_edges, plane, point_in_convex, quaternion_matrix, read_obj,
    rocking_geometry, rotation_between, settle, sig9)


WRITE_HULL = True  # --no-hull clears it: entries without the hull key


def entry_3d(g):
    """The entry's 3-D keys (floor frame, module docstring), one per line."""
    c, i = g["com"], g["inertia"]
    poly = ", ".join(f"[{fmt(x)}, {fmt(y)}]" for x, y in g["base_polygon"])
    rows = ", ".join("[" + ", ".join(fmt(i[r][k]) for k in range(3)) + "]" for r in range(3))
    shift = "" if not g.get("com_shift") else \
        f", shifted by ({fmt(g['com_shift'][0])}, {fmt(g['com_shift'][1])}) m after placement"
    return [f"    mass: {fmt(g['mass'])}   # kg",
            f"    centre_of_mass: [{fmt(c[0])}, {fmt(c[1])}, {fmt(c[2])}]   # m, floor frame{shift}",
            f"    base_polygon: [{poly}]   # m, contact hull, counter-clockwise from above",
            *([] if not (WRITE_HULL and g.get("contact_hull")) else [
                "    hull: [" + ", ".join("[" + ", ".join(fmt(x) for x in p) + "]" for p in g["contact_hull"]) +
                "]   # m, the convex hull above the base (floor frame): the contact as the body tilts beyond it"]),
            f"    central_inertia: [{rows}]   # kg m^2, about the centre of mass (the homogeneous "
            "mesh's about that point)"]


def catalogue_entry(item_id, g, sensor="table", restitution_shift=None, mu_s=None, planar_only=False,
                    extra=()):
    """YAML text of a catalogue item (both planes and the 3-D description), with the derivation in
    comments; an ensemble member may also carry its restitution_shift (added to eq. 34 per pivot) and
    mu_s. planar_only: without the 3-D keys."""
    x, y = g["x"], g["y"]
    lines = [f"  - id: {item_id}",
             f"    sensor: {sensor}",
             f"    width: {x['width']:.9g}          # m, base contact extent along the shaking axis (x)",
             f"    depth: {y['width']:.9g}          # m, across it (y)",
             f"    cg_height: {x['cg_height']:.9g}      # m, centre of mass above the lowest vertex",
             f"    eccentricity: {x['eccentricity']:.9g}",
             f"    eccentricity_y: {y['eccentricity']:.9g}",
             f"    radius_of_gyration: {x['radius_of_gyration']:.9g}   # m, central, about y",
             f"    radius_of_gyration_y: {y['radius_of_gyration']:.9g} # m, central, about x"]
    for name, p in (("x", x), ("y", y)):
        for k, piv in enumerate(p["pivots"], 1):
            lines.append(f"    # {name}-plane pivot {k}: alpha {math.degrees(piv['alpha']):.4f} deg, R "
                         f"{piv['radius']:.6f} m, I_O {piv['inertia']:.4f} kg m^2")
    if not planar_only:
        lines += entry_3d(g)
    lines += list(extra)  # a scan's decisions (comments) and its hull (scan_entry.py)
    if restitution_shift is not None:
        lines.append(f"    restitution_shift: {restitution_shift:.6f}   # added to eq. 34's ratio of each pivot")
    if mu_s is not None:
        lines.append(f"    mu_s: {mu_s:.6f}   # static friction, granite on the table")
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- the granite specimens

# Placements from ../shared/experiments/granite_pbr/README.md (Virtual Shake Robot configuration).
GRANITE = {
    "SP1": {"mesh": "specimens/SP1_pca.obj.gz",
            "quaternion": (0.8676640240119536, 0.06594471044608025, 0.4791004506761131,
                           0.11520935188391664),
            "mass": 353.802, "com": None},
    "SP2": {"mesh": "specimens/SP2.obj.gz", "quaternion": (0.0, 0.0, 0.0, 1.0),
            "mass": 353.802, "com": (-0.033, 0.029, 0.001)},
}
# The centre of mass the Virtual Shake Robot's PyBullet model simulates (--urdf-com), mesh frame, m. SP2's
# sp2.urdf (HEAD 9f239e7) loads this very mesh (final_sp2_1.obj, the same bytes as specimens/SP2.obj.gz)
# at scale 1, rpy 0, with its visual/collision origin at xyz (-0.033, 0.029, 0.001) and the inertial
# origin at 0: the mesh sits at that offset from the centre of mass, so the centre is at minus it in
# the mesh frame. (The offset is the centroid of an older, uncentred copy of the scan, in cm and turned
# by 54 deg about z; docs/validation.md, "SP2's third centre of mass".) SP1's sp1.urdf has both origins
# at 0 on the principal-frame mesh, whose centroid is the origin: the homogeneous centre.
URDF_COM = {"SP1": None, "SP2": (0.033, -0.029, -0.001)}


def plot_outline(path, title, placed, g):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4.6))
    step = max(1, len(placed) // 6000)
    pts = placed[::step]
    ax1.scatter(pts[:, 0], pts[:, 2], s=0.3, c="0.6")
    c = g["com"]
    for piv, col in zip(g["x"]["pivots"], ("tab:red", "tab:blue")):
        p = piv["point"]
        ax1.plot([p[0], c[0]], [p[2], c[2]], "-", color=col,
                 label=f"pivot: alpha {math.degrees(piv['alpha']):.1f} deg, R {piv['radius']:.3f} m")
        ax1.plot(p[0], p[2], "o", color=col)
    ax1.plot(c[0], c[2], "k*", ms=12, label="centre of mass")
    ax1.axhline(0, color="k", lw=0.8)
    ax1.set_aspect("equal")
    ax1.set_xlabel("x, shaking axis (m)")
    ax1.set_ylabel("z (m)")
    ax1.set_title(f"{title}: side view (x-z)")
    ax1.legend(fontsize=7, loc="upper right")
    low = placed[placed[:, 2] <= 0.05]
    ax2.scatter(low[:, 0], low[:, 1], s=0.5, c="0.75", label="vertices below 50 mm")
    hull = np.asarray(g["hull"])
    if len(hull) >= 3:
        closed = np.vstack([hull, hull[:1]])
        ax2.plot(closed[:, 0], closed[:, 1], "g-", label="base contact hull")
    for piv, col in zip(g["x"]["pivots"], ("tab:red", "tab:blue")):
        ax2.plot(piv["point"][0], piv["point"][1], "o", color=col)
    ax2.plot(c[0], c[1], "k*", ms=12)
    ax2.set_aspect("equal")
    ax2.set_xlabel("x, shaking axis (m)")
    ax2.set_ylabel("y (m)")
    ax2.set_title(f"base, tolerance {g['contact_tolerance'] * 1000:g} mm")
    ax2.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def specimen_specs(homogeneous=False, names=None, urdf_com=False):
    """GRANITE, optionally every centre of mass homogeneous (or the URDF's, URDF_COM) and only the
    named specimens."""
    if homogeneous and urdf_com:
        raise GeometryError("--homogeneous and --urdf-com: one centre of mass at a time")
    names = list(GRANITE) if not names else list(names)
    for n in names:
        if n not in GRANITE:
            raise GeometryError(f"--specimen {n}: not one of {', '.join(GRANITE)}")
    def com(n):
        return None if homogeneous else URDF_COM[n] if urdf_com else GRANITE[n]["com"]
    return {n: dict(GRANITE[n], com=com(n)) for n in names}


def granite(directory, tolerance, plot_dir=None, settle_on_hull=True, homogeneous=False,
            com_shift=None, names=None, planar_only=False, urdf_com=False):
    entries, results = [], {}
    for name, spec in specimen_specs(homogeneous, names, urdf_com).items():
        v, f = read_obj(os.path.join(directory, spec["mesh"]))
        try:
            g, placed = rocking_geometry(v, f, quaternion_matrix(*spec["quaternion"]), spec["mass"],
                                         tolerance, spec["com"], settle_on_hull, com_shift)
        except GeometryError as e:
            raise GeometryError(f"{name}: {e}")
        g["open_edges"] = open_edges(v, f)
        # No hull key: in these tests the specimens stood on a pedestal, whose top bounds the contact;
        # the hull on an unbounded floor holds them up where they fell (docs/validation.md).
        g.pop("contact_hull", None)
        results[name] = g
        entries.append(catalogue_entry(name, g, planar_only=planar_only))
        if plot_dir:
            plot_outline(os.path.join(plot_dir, f"granite_{name}.png"), name, placed, g)
    return results, entries


def granite_ensemble(directory, members, seed, tolerance, max_tilt_deg=5.0, tol_range=(5e-4, 2e-3),
                     restitution_spread=0.05, mu_range=(0.5, 0.8), homogeneous=False, com_shift=None,
                     names=None, planar_only=False, urdf_com=False):
    """Members of each specimen's geometric uncertainty, member 0 the nominal (granite()): the
    placement tilted by up to max_tilt_deg about a random horizontal axis (the configuration's
    orientation is itself uncertain) then settled, the contact tolerance log-uniform in tol_range,
    and for SP2 either of the data's two centres of mass (stated, or the homogeneous mesh's).
    Members k > 0 also get a restitution shift uniform in +-restitution_spread (added to eq. 34 of
    each pivot; 0 = not sampled) and mu_s uniform in mu_range (None = not sampled: pure rocking),
    each from its own generator so that the geometry draws do not depend on them.
    Returns the YAML entries (ids SP1#k) and the number of members refused (no resting face or a
    line contact), which are reported, not replaced. com_shift moves every member's centre of mass.
    With names, only those specimens (the draws are then not those of the full ensemble's)."""
    rng = np.random.default_rng(seed)
    rng_e = np.random.default_rng([seed, 1])
    rng_mu = np.random.default_rng([seed, 2])
    entries, refused = [], 0
    for name, spec in specimen_specs(homogeneous, names, urdf_com).items():
        v, f = read_obj(os.path.join(directory, spec["mesh"]))
        q = quaternion_matrix(*spec["quaternion"])
        for k in range(members):
            rot, tol, com = q, tolerance, spec["com"]
            shift = mu = None
            if k > 0:
                # drawn first so every member consumes the same draws, refused or not
                de = rng_e.uniform(-restitution_spread, restitution_spread)
                dm = rng_mu.uniform(*mu_range) if mu_range else None
                shift = de if restitution_spread > 0 else None
                mu = dm
                phi = rng.uniform(0.0, 2.0 * math.pi)
                tilt = math.radians(rng.uniform(-max_tilt_deg, max_tilt_deg))
                axis = np.array([math.cos(phi), math.sin(phi), 0.0])
                qt = (*(axis * math.sin(tilt / 2)), math.cos(tilt / 2))
                rot = quaternion_matrix(*qt) @ q
                tol = math.exp(rng.uniform(math.log(tol_range[0]), math.log(tol_range[1])))
                if spec["com"] is not None and rng.uniform() < 0.5:
                    com = None
            try:
                g, _ = rocking_geometry(v, f, rot, spec["mass"], tol, com, True, com_shift)
            except GeometryError as e:
                refused += 1
                print(f"rocking_geometry: {name} member {k} refused: {e}", file=sys.stderr)
                continue
            g.pop("contact_hull", None)  # on a pedestal, as granite() says
            entries.append(catalogue_entry(f"{name}#{k}", g, restitution_shift=shift, mu_s=mu,
                                           planar_only=planar_only))
    return entries, refused


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh", nargs="?", help="mesh or scan: PLY, STL, OBJ, OFF, glTF, GLB (.gz allowed)")
    ap.add_argument("--granite", metavar="DIR", help="the granite_pbr data set: both specimens")
    ap.add_argument("--quaternion", nargs=4, type=float, metavar=("X", "Y", "Z", "W"),
                    help="placement rotation, mesh -> world (then --floor given)")
    ap.add_argument("--unit", choices=["auto", "m", "mm", "cm", "in"], default="auto",
                    help="the mesh file's length unit (default auto: mm when its largest extent is "
                         "over 10 units, else m; stated)")
    ap.add_argument("--up", choices=["x", "y", "z", "-x", "-y", "-z"],
                    help="the mesh file's up axis (default z; y for glTF/GLB)")
    ap.add_argument("--floor", choices=["auto", "lowest", "largest", "given"], default="auto",
                    help="what it stands on: lowest (default) the convex-hull face nearest to -up that "
                         "carries the centre of mass; largest: the largest such face; given: the "
                         "--quaternion placement (the default when --quaternion is given)")
    ap.add_argument("--keep-slab", action="store_true",
                    help="keep a wide flat bottom layer (default: a scanned floor or turntable is "
                         "recognised and removed, and the removal stated)")
    ap.add_argument("--cap-tolerance", type=float, metavar="M",
                    help="a hole is capped when it lies within M of the floor (default max(3 x "
                         "contact tolerance, 2 %% of the height)); elsewhere the mesh is refused")
    ap.add_argument("--sensor", default="table", help="the entry's sensor (default table)")
    ap.add_argument("--write-hull", action="store_true",
                    help="(the default now; kept for old command lines)")
    ap.add_argument("--no-hull", action="store_true",
                    help="without the hull key: the body rocks on its base polygon only (as before the "
                         "3-D model knew the hull)")
    ap.add_argument("--mass", type=float, default=1.0, help="kg (default 1)")
    ap.add_argument("--com", nargs=3, type=float, help="measured centre of mass, mesh frame, m")
    ap.add_argument("--contact-tolerance", type=float, default=0.001,
                    help="m above the lowest vertex counted as base contact (default 0.001: "
                         "scan noise on a resting face)")
    ap.add_argument("--settle", action="store_true",
                    help="turn the body onto the convex-hull face it rests on nearest to the placement "
                         "(always on with --granite unless --no-settle)")
    ap.add_argument("--no-settle", action="store_true", help="with --granite: use the placement as given")
    ap.add_argument("--homogeneous", action="store_true",
                    help="with --granite: the mesh's own centre of mass for every specimen")
    ap.add_argument("--urdf-com", action="store_true",
                    help="with --granite: the centre of mass the Virtual Shake Robot's URDF simulates "
                         "(SP2: (+0.033, -0.029, -0.001) m in the mesh frame, the stated one's opposite; "
                         "SP1: the homogeneous)")
    ap.add_argument("--specimen", action="append", metavar="NAME",
                    help="with --granite: only this specimen (repeatable; default all)")
    ap.add_argument("--com-shift", nargs=2, type=float, metavar=("DX", "DY"),
                    help="move the centre of mass by DX, DY m (floor frame, horizontal) after "
                         "placement and settling: the scanned rock's centre is uncertain (calibration)")
    ap.add_argument("--planar-only", action="store_true",
                    help="omit the 3-D keys (mass, centre_of_mass, base_polygon, central_inertia): "
                         "for a rocking_experiments/monitor built before its reader knew them")
    ap.add_argument("--ensemble", type=int, default=0, metavar="N",
                    help="with --granite: N members per specimen of its geometric uncertainty "
                         "(ids SP1#k; rocking_experiments gives P(overturn))")
    ap.add_argument("--seed", type=int, default=20, help="ensemble seed (default 20)")
    ap.add_argument("--restitution-spread", type=float, default=0.05, metavar="D",
                    help="ensemble: restitution shift uniform in +-D around eq. 34 per pivot (default "
                         "0.05; 0 = not sampled)")
    ap.add_argument("--mu-s", nargs=2, type=float, default=(0.5, 0.8), metavar=("LO", "HI"),
                    help="ensemble: static friction uniform in [LO, HI] (default 0.5 0.8, granite on "
                         "steel); --no-friction: not sampled (pure rocking)")
    ap.add_argument("--no-friction", action="store_true", help="ensemble: no mu_s (pure rocking)")
    ap.add_argument("--id", default="item")
    ap.add_argument("--yaml", help="write the catalogue (items:) here")
    ap.add_argument("--json", help="write every number here")
    ap.add_argument("--plot-dir", help="outline pictures (PNG) here")
    a = ap.parse_args(argv)
    # Neither input: the usage error, as before (--homogeneous & co. without --granite are the run's
    # GeometryError, exit 2), so that the run steps need no parser.
    if not a.granite and not a.mesh and not (a.homogeneous or a.urdf_com or a.specimen):
        ap.error("give a MESH or --granite DIR")
    return a


def granite_entries(a):
    """--granite: (results, entries) of the specimens, or of their --ensemble members."""
    if a.ensemble > 0:
        if not 0.0 <= a.restitution_spread <= 1.0:
            raise GeometryError(f"--restitution-spread {a.restitution_spread}: must lie in [0, 1]")
        if not 0.0 <= a.mu_s[0] <= a.mu_s[1]:
            raise GeometryError(f"--mu-s {a.mu_s[0]} {a.mu_s[1]}: need 0 <= LO <= HI")
        entries, refused = granite_ensemble(
            a.granite, a.ensemble, a.seed, a.contact_tolerance,
            restitution_spread=a.restitution_spread,
            mu_range=None if a.no_friction else tuple(a.mu_s), homogeneous=a.homogeneous,
            com_shift=a.com_shift, names=a.specimen, planar_only=a.planar_only,
            urdf_com=a.urdf_com)
        results = {}
        print(f"rocking_geometry: {len(entries)} members written, {refused} refused",
              file=sys.stderr)
    else:
        results, entries = granite(a.granite, a.contact_tolerance, a.plot_dir, not a.no_settle,
                                   a.homogeneous, a.com_shift, a.specimen, a.planar_only,
                                   a.urdf_com)
    return results, entries


def mesh_entries(a):
    """MESH: (results, entries) of the one scan (scan_entry.py), its outline with --plot-dir."""
    import scan_entry  # noqa: E402  (beside this script)
    g, placed, notes = scan_entry.scan_geometry(
        a.mesh, a.mass, a.contact_tolerance, a.com, a.unit, a.up, a.floor, a.keep_slab,
        a.cap_tolerance, a.quaternion, a.settle, a.com_shift)
    for n in notes + [scan_entry.describe(g)]:
        print(f"rocking_geometry: {a.mesh}: {n}", file=sys.stderr)
    extra = scan_entry.entry_comments(g)
    results = {a.id: g}
    entries = [catalogue_entry(a.id, g, a.sensor, planar_only=a.planar_only, extra=extra)]
    if a.plot_dir:
        plot_outline(os.path.join(a.plot_dir, f"{a.id}.png"), a.id, placed, g)
    return results, entries


def write_outputs(a, argv, results, entries):
    """The catalogue text (--yaml or stdout), open-mesh warnings, every number (--json)."""
    made_by = " ".join(["rocking_geometry.py"] + list(sys.argv[1:] if argv is None else argv))
    text = ("# rocking_geometry: catalogue entries derived from meshes "
            f"(contact tolerance {a.contact_tolerance} m)\n# made by: {made_by}\nitems:\n" + "".join(entries))
    if a.yaml:
        with open(a.yaml, "w") as out:
            out.write(text)
    else:
        sys.stdout.write(text)
    for name, g in results.items():
        if g["open_edges"]:
            print(f"rocking_geometry: warning: {name}: {g['open_edges']} open edges: the mesh is not "
                  "closed, its volume integrals are approximate", file=sys.stderr)
    if a.json:
        with open(a.json, "w") as out:
            json.dump(results, out, indent=1)


def run_geometry(a, argv=None):
    global WRITE_HULL
    WRITE_HULL = not a.no_hull
    try:
        if not a.granite and (a.homogeneous or a.urdf_com or a.specimen):
            raise GeometryError("--homogeneous, --urdf-com and --specimen need --granite DIR")
        if a.granite:
            results, entries = granite_entries(a)
        else:
            results, entries = mesh_entries(a)
    except GeometryError as e:
        print(f"rocking_geometry: {e}", file=sys.stderr)
        return 2
    write_outputs(a, argv, results, entries)
    return 0


def main(argv=None):
    return run_geometry(parse_args(argv), argv)


if __name__ == "__main__":
    sys.exit(main())
