"""scan_entry: a scan (or any mesh file) to rocking_geometry's quantities (issue 43).

The file is read and checked (mesh_input), scaled to metres, a scanned floor or turntable removed,
open holes capped, then stood on its floor: by default the convex-hull face nearest to straight down
along the file's up axis (+z; +y for glTF, whose specification says so) that carries the centre of
mass; --floor largest: the largest convex-hull face that carries it; --floor given: the placement as
given (--quaternion). A capped hole must lie at that floor (within the cap tolerance): a scan open
elsewhere is refused. Every decision is returned as a note, for the user and the YAML's comments.
"""
import math

import numpy as np

import mesh_input as mi
import rocking_geometry_solid as rg  # not rocking_geometry.py: it imports this module

AXES = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1), "-x": (-1, 0, 0), "-y": (0, -1, 0), "-z": (0, 0, -1)}
DOWN = np.array([0.0, 0.0, -1.0])


def rotation_onto(a, b):
    """rg.rotation_between, also for opposite vectors (a half turn about a perpendicular axis)."""
    a, b = np.asarray(a, float) / np.linalg.norm(a), np.asarray(b, float) / np.linalg.norm(b)
    if np.dot(a, b) < -1 + 1e-12:
        axis = np.cross(a, [1.0, 0, 0] if abs(a[0]) < 0.9 else [0, 1.0, 0])
        axis /= np.linalg.norm(axis)
        return 2 * np.outer(axis, axis) - np.eye(3)
    return rg.rotation_between(a, b)


def largest_face_rotation(vertices, faces, com, tolerance):
    """The rotation standing the body on its largest convex-hull face (coplanar hull triangles
    summed) whose contact polygon carries the centre of mass; and that face's area, m^2."""
    from scipy.spatial import ConvexHull
    pts = vertices[np.unique(faces)]
    hull = ConvexHull(pts)
    tri = pts[hull.simplices]
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    scale = float(np.ptp(pts, axis=0).max())
    keys = np.round(np.hstack([hull.equations[:, :3], hull.equations[:, 3:] / scale]), 6)
    groups = {}
    for k, key in enumerate(map(tuple, keys)):
        groups.setdefault(key, [0.0, hull.equations[k, :3]])[0] += area[k]
    for total, n in sorted(groups.values(), key=lambda g: -g[0]):
        r = rotation_onto(n, DOWN)
        p, c = pts @ r.T, r @ com
        low = p[p[:, 2] <= p[:, 2].min() + tolerance]
        poly = rg.convex_hull_2d(low[:, :2])
        if len(poly) >= 3 and rg.point_in_convex(poly, c[:2]):
            return r, total
    raise mi.GeometryError("no convex-hull face carries the centre of mass: the body cannot rest")


def scan_geometry(path, mass=1.0, tolerance=1e-3, com=None, unit="auto", up=None, floor="auto",
                  keep_slab=False, cap_tolerance=None, quaternion=None, settle=False, com_shift=None,
                  keep_mesh=False, progress=None):
    """(g, placed, notes): rocking_geometry's result for the mesh file at `path`, the placed vertices
    (floor frame) and the statements of what was decided. com: measured centre of mass in the mesh's
    frame, metres (after the unit conversion). progress: called with each of STAGES as it begins
    (rocking_catalogue's bar: a big scan takes a minute, most of it in the surface check)."""
    begin = progress or (lambda stage: None)
    if unit != "auto" and unit not in mi.UNITS:
        raise mi.GeometryError(f"unit '{unit}': one of auto, {', '.join(mi.UNITS)}")
    if up is not None and up not in AXES:
        raise mi.GeometryError(f"up axis '{up}': one of {', '.join(AXES)}")
    v, f, notes = _read_in_metres(path, unit, begin)
    if floor == "auto":
        floor = "given" if quaternion is not None else "lowest"
    if up is None:
        up = "y" if mi.FORMATS.get(_ext(path)) == "gltf" else "z"
    start = (rg.quaternion_matrix(*quaternion) if quaternion is not None
             else rotation_onto(AXES[up], (0, 0, 1)))
    removed = f[:0]
    begin(STAGES[2])
    if not keep_slab:
        keep, note = mi.find_slab(v, f, start.T @ np.array([0.0, 0, 1]))
        notes.append(note)
        if keep is not None:
            removed, f = f[~keep], f[keep]
    v_all = v
    used, f = np.unique(f, return_inverse=True)  # only the vertices of faces: the floor is theirs
    v, f = v[used], f.reshape(-1, 3)
    begin(STAGES[3])
    loops, unchecked = mi.check_solid(v, f, path)
    if unchecked:
        notes.append("self-intersection not checked: too many candidate triangle pairs")
    vc, fc = mi.cap_loops(v, f, loops)
    begin(STAGES[4])
    try:
        volume, com_mesh, _ = rg.mass_properties(vc, fc)
    except mi.GeometryError:  # exactly zero
        volume, com_mesh = 0.0, None
    cube = float(np.ptp(vc, axis=0).max()) ** 3
    if not volume > 1e-6 * cube:
        raise mi.GeometryError(f"{path}: degenerate: encloses {volume:.3g} m^3, {volume / cube:.2g} of the "
                               "cube of its largest extent (a flat sheet or a collapsed mesh, not a solid)")
    if loops:
        notes.append(f"open: {len(loops)} hole(s), {sum(map(len, loops))} boundary edges, each capped")
    else:
        notes.append("closed surface")
    c0 = com_mesh if com is None else np.asarray(com, float)
    rotation, do_settle, why = _floor_choice(floor, start, settle, up, vc, fc, c0, tolerance)
    begin(STAGES[5])
    g, placed = rg.rocking_geometry(vc, fc, rotation, mass, tolerance, com, do_settle, com_shift)
    notes.append(why + (f", turned {g['settle_angle_deg']:.3g} deg onto it" if do_settle else ""))
    height = float(placed[:, 2].max())
    cap_tol = cap_tolerance if cap_tolerance is not None else max(3 * tolerance, 0.02 * height)
    for loop in loops:
        top = float(placed[loop, 2].max())
        if top > cap_tol:
            raise mi.GeometryError(
                f"{path}: open elsewhere than at its base: a hole of {len(loop)} edges reaches "
                f"{top * 1000:.4g} mm above the floor (cap tolerance {cap_tol * 1000:.3g} mm); only a hole "
                "at the base is capped: fill this one in the scanning software (or check --up / --floor)")
    if loops:
        notes.append(f"the hole(s) lie at the floor (within {cap_tol * 1000:.3g} mm)")
    g["open_edges"] = len(mi.edge_report(fc)[2])  # 0: every hole was capped
    g["notes"] = notes
    g["size"] = np.ptp(placed, axis=0).tolist()
    begin(STAGES[6])
    g["convex_hull"] = convex_hull_3d(placed[np.unique(fc)])
    if keep_mesh:  # for pictures (not JSON): the capped mesh and the removed slab, floor frame
        r, floor_z = np.array(g["rotation"]), float((vc @ np.array(g["rotation"]).T)[:, 2].min())
        g["_mesh"] = {"vertices": placed, "faces": fc, "caps": len(fc) - len(f),
                      "removed": v_all[removed] @ r.T - [0.0, 0.0, floor_z]}
    return g, placed, notes


def _floor_choice(floor, start, settle, up, vc, fc, c0, tolerance):
    """(rotation, settle onto it, the note saying why) for --floor given | lowest | largest."""
    if floor == "given":
        return start, settle, "floor: the placement as given (--quaternion)" + (", settled" if settle else "")
    if floor == "lowest":
        return start, True, (f"floor: the convex-hull face nearest to straight down along -{up} that carries "
                              "the centre of mass")
    if floor == "largest":
        rotation, area = largest_face_rotation(vc, fc, c0, tolerance)
        return rotation, True, f"floor: the largest convex-hull face carrying the centre of mass ({area:.4g} m^2)"
    raise mi.GeometryError(f"--floor {floor}: one of auto, lowest, largest, given")


# scan_geometry's steps in order, as its progress callback names them.
STAGES = ("reading", "merging vertices", "floor slab", "checking the surface", "mass properties",
          "placing on the floor", "convex hull")


def _read_in_metres(path, unit, begin):
    """(vertices in metres, faces, notes): the file read, its unit settled, coincident vertices merged
    and degenerate triangles dropped."""
    begin(STAGES[0])
    v, f, notes = mi.read_mesh(path)
    scale, note = mi.unit_scale(v, f, unit, path)
    notes.append(note)
    v = v * scale
    begin(STAGES[1])
    size = float(np.ptp(v[np.unique(f)], axis=0).max())
    v, f, dropped = mi.merge_vertices(v, f, 1e-9 * max(size, 1.0))
    if not len(f):
        raise mi.GeometryError(f"{path}: degenerate: every triangle has zero area (a line or a point)")
    if dropped:
        notes.append(f"{dropped} degenerate triangles (zero area or a repeated vertex) dropped")
    return v, f, notes


def convex_hull_3d(points):
    """The convex hull's vertices (floor frame, m), in qhull's order."""
    from scipy.spatial import ConvexHull
    return points[ConvexHull(points).vertices].tolist()


def _ext(path):
    import os
    name = path[:-3] if path.endswith(".gz") else path
    return os.path.splitext(name)[1].lower()


def entry_comments(g):
    """The scan's decisions and the contact tolerance, as YAML comment lines of the entry."""
    size = " x ".join(f"{s * 1000:.0f}" for s in g["size"])
    lines = [f"    # from the scan: {size} mm (x, y, z), mass {g['mass']:g} kg, contact tolerance "
             f"{g['contact_tolerance'] * 1000:g} mm ({g['contact_points']} base points)"]
    lines += [f"    #   {n}" for n in g["notes"]]
    return [ln[:200] for ln in lines]


def hull_line(g):
    pts = ", ".join("[" + ", ".join(rg.fmt(x) for x in p) + "]" for p in g["convex_hull"])
    return f"    hull: [{pts}]   # m, convex hull of the mesh, floor frame (as base_polygon)"


def describe(g):
    """Short human summary for stderr."""
    x, y = g["x"], g["y"]
    return (f"alpha {math.degrees(min(p['alpha'] for p in x['pivots'])):.2f} deg (x), "
            f"{math.degrees(min(p['alpha'] for p in y['pivots'])):.2f} deg (y); base polygon "
            f"{len(g['base_polygon'])} vertices")
