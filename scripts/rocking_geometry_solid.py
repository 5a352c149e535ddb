"""rocking_geometry_solid: the solid-geometry half of rocking_geometry.py (issues 20, 43, 42).

A mesh's mass properties (signed tetrahedra), its placement (settling onto a convex-hull face), the
base contact's convex hull and the per-plane pivots, and the hull above the base, all in the floor
frame rocking_geometry.py's docstring defines; rocking_geometry() gathers them for one placed mesh.
rocking_geometry.py imports every name here and re-exports it (rg.mass_properties etc. keep working);
scan_entry.py imports this module, not rocking_geometry.py, which imports scan_entry (no circle).
"""
import math

import numpy as np

from mesh_input import GeometryError, read_mesh  # noqa: E402  (beside this script)


# ---------------------------------------------------------------- reading

def read_obj(path):
    """Vertices (n x 3) and triangles (m x 3, 0-based) of a mesh file in metres, as stored (PLY, STL,
    OBJ, OFF, glTF/GLB, .gz allowed; mesh_input.read_mesh: meshio and assimp, polygons fanned)."""
    v, f, _ = read_mesh(path)
    return v, f


def open_edges(vertices, faces):
    """Directed edges without their opposite twin, after merging coincident vertices (scanner
    exports often duplicate vertices per face). 0 for a closed, consistently oriented surface."""
    _, inverse = np.unique(vertices, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    f = inverse[faces]
    directed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    directed = directed[directed[:, 0] != directed[:, 1]]
    keys = set(map(tuple, directed.tolist()))
    return sum(1 for a, b in keys if (b, a) not in keys)


# ---------------------------------------------------------------- mass properties

def mass_properties(vertices, faces):
    """Volume, centre of mass and second moment (integral of x x^T dV) of the closed surface, exact:
    sum over signed tetrahedra (origin, a, b, c). Orientation is fixed so that the volume is > 0."""
    a, b, c = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
    det = np.einsum("ij,ij->i", a, np.cross(b, c))  # 6 x signed volume
    volume = det.sum() / 6.0
    if volume == 0.0:
        raise GeometryError("mesh encloses zero volume")
    s = a + b + c
    first = (det[:, None] * s).sum(axis=0) / 24.0  # integral of x dV
    # integral over tet(0,a,b,c) of x_i x_j = det/120 (sum_k v_k,i v_k,j + s_i s_j)
    second = (np.einsum("n,ni,nj->ij", det, a, a) + np.einsum("n,ni,nj->ij", det, b, b)
              + np.einsum("n,ni,nj->ij", det, c, c) + np.einsum("n,ni,nj->ij", det, s, s)) / 120.0
    sign = 1.0 if volume > 0 else -1.0
    return sign * volume, first / volume, sign * second


def central_inertia(volume, com, second, mass):
    """Inertia tensor about the centre of mass, kg m^2, for a homogeneous body of this mass."""
    rho = mass / volume
    c = rho * second - mass * np.outer(com, com)  # central second moment
    return np.trace(c) * np.eye(3) - c


def quaternion_matrix(x, y, z, w):
    n = math.sqrt(x * x + y * y + z * z + w * w)
    if not n > 0:
        raise GeometryError("quaternion has zero norm")
    x, y, z, w = x / n, y / n, z / n, w / n
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


# ---------------------------------------------------------------- base contact and pivots

def convex_hull_2d(points):
    """Andrew's monotone chain; counter-clockwise hull of (n x 2) points, collinear points dropped."""
    pts = sorted(set(map(tuple, np.asarray(points).tolist())))
    if len(pts) <= 2:
        return np.asarray(pts)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.asarray(lower[:-1] + upper[:-1])


def plane(contact, com, inertia, mass, axis):
    """Rocking in the vertical plane containing world axis `axis` (0 = x, 1 = y).
    Pivot 1 is the contact point with the smallest coordinate (the catalogue's corner 1), pivot 2
    the largest. Inertia about each pivot: about the horizontal axis perpendicular to the plane."""
    coord = contact[:, axis]
    i1, i2 = int(np.argmin(coord)), int(np.argmax(coord))
    p1, p2 = contact[i1], contact[i2]
    width = p2[axis] - p1[axis]
    name = "xy"[axis]
    if not width > 0:
        raise GeometryError(f"base contact has no extent along {name} (a line across the shaking "
                            f"axis): increase --contact-tolerance or check the placement")
    b1, b2 = com[axis] - p1[axis], p2[axis] - com[axis]
    if not (b1 > 0 and b2 > 0):
        raise GeometryError(f"centre of mass ({name} = {com[axis]:.6g} m) is not over the base "
                            f"contact [{p1[axis]:.6g}, {p2[axis]:.6g}] m: the placement is not at rest")
    perp = 1 - axis  # rotation axis is the other horizontal axis
    i_c = inertia[perp, perp]
    floor = contact[:, 2].min()
    h = com[2] - floor
    out = {"width": width, "cg_height": h, "eccentricity": b1 / width,
           "radius_of_gyration": math.sqrt(i_c / mass), "central_inertia": i_c, "pivots": []}
    for p, b in ((p1, b1), (p2, b2)):
        hp = com[2] - p[2]  # the pivot's own height may sit up to the tolerance above the floor
        out["pivots"].append({
            "point": p.tolist(), "lever": b, "alpha": math.atan2(b, h), "radius": math.hypot(b, h),
            "inertia": i_c + mass * (b * b + h * h),
            "alpha_own_height": math.atan2(b, hp), "radius_own_height": math.hypot(b, hp)})
    return out


def rotation_between(a, b):
    """Smallest rotation taking unit vector a onto unit vector b (Rodrigues)."""
    a, b = a / np.linalg.norm(a), b / np.linalg.norm(b)
    v, c = np.cross(a, b), float(np.dot(a, b))
    s = np.linalg.norm(v)
    if s < 1e-15:
        return np.eye(3)  # a == -b does not occur: the candidates are within 90 deg of -z
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]]) / s
    angle = math.atan2(s, c)
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * (k @ k)


def settle(placed, com, tolerance):
    """The rest position nearest to the given placement: a rigid body on a flat floor rests on a face
    of its convex hull, the one whose normal is closest to straight down among those with the centre
    of mass above the contact polygon. Returns the small rotation to apply (world frame) and its
    angle, rad; the given placement is then only the starting guess (a scan's orientation on the
    table is known to about a degree)."""
    from scipy.spatial import ConvexHull
    hull = ConvexHull(placed)
    normals = hull.equations[:, :3]
    down = np.array([0.0, 0.0, -1.0])
    order = np.argsort(-(normals @ down))
    tried = set()
    for i in order:
        n = normals[i]
        if n @ down <= 0:
            break
        key = tuple(np.round(n, 9))
        if key in tried:
            continue
        tried.add(key)
        r = rotation_between(n, down)
        p = placed @ r.T
        c = r @ com
        low = p[p[:, 2] <= p[:, 2].min() + tolerance]
        h2 = convex_hull_2d(low[:, :2])
        if len(h2) >= 3 and point_in_convex(h2, c[:2]):
            return r, math.acos(min(1.0, float(n @ down)))
    raise GeometryError("no convex-hull face carries the centre of mass: the body cannot rest")


def point_in_convex(hull, p):
    """p strictly inside the counter-clockwise convex polygon."""
    for k in range(len(hull)):
        a, b = hull[k], hull[(k + 1) % len(hull)]
        if (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) <= 0:
            return False
    return True


# A base_polygon vertex closer than this to the chord of its neighbours, or to its predecessor, is
# dropped: far below a scan's resolution, and far above the 1e-10 m of the 9 printed digits, so the
# printed polygon stays strictly convex (the 3-D catalogue reader rejects collinear vertices).
POLYGON_TOLERANCE = 1e-6


def sig9(x):
    """x as printed with 9 significant digits, back as a float (what the YAML reader sees)."""
    return float(f"{x:.9g}")


# The 3-D reader's limit (physics/base_body.hpp, kMaxBaseVertices).
MAX_BASE_VERTICES = 64


def base_polygon(hull, tolerance=POLYGON_TOLERANCE, max_vertices=MAX_BASE_VERTICES):
    """The hull as written: rounded to 9 digits, counter-clockwise, vertices within `tolerance` of
    their neighbours' chord (or of their predecessor) dropped. Raises if fewer than 3 remain.
    Beyond max_vertices, the vertex cutting off the smallest triangle goes first (the polygon only
    shrinks: the base errs toward less stable)."""
    pts = convex_hull_2d([[sig9(x), sig9(y)] for x, y in np.asarray(hull).tolist()])
    pts = [tuple(p) for p in np.asarray(pts).tolist()]
    changed = True
    while changed and len(pts) >= 3:
        changed = False
        for k in range(len(pts)):
            a, b, c = np.array(pts[k - 1]), np.array(pts[k]), np.array(pts[(k + 1) % len(pts)])
            chord = c - a
            length = np.linalg.norm(chord)
            off = abs(chord[0] * (b - a)[1] - chord[1] * (b - a)[0]) / length if length > 0 else 0.0
            if np.linalg.norm(b - a) < tolerance or off < tolerance:
                del pts[k]
                changed = True
                break
    while len(pts) > max_vertices:
        area = [abs((pts[k][0] - pts[k - 1][0]) * (pts[(k + 1) % len(pts)][1] - pts[k - 1][1])
                    - (pts[k][1] - pts[k - 1][1]) * (pts[(k + 1) % len(pts)][0] - pts[k - 1][0]))
                for k in range(len(pts))]
        del pts[int(np.argmin(area))]
    if len(pts) < 3:
        raise GeometryError(f"base contact polygon has {len(pts)} vertices after dropping collinear ones "
                            f"(a point or a line): increase --contact-tolerance or check the placement")
    # convex_hull_2d is counter-clockwise and dropping vertices keeps it convex: a check, not a repair
    for k in range(len(pts)):
        (ax, ay), (bx, by), (cx, cy) = pts[k - 2], pts[k - 1], pts[k]
        if not (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) > 0:
            raise GeometryError("base contact polygon is not strictly convex counter-clockwise")
    return [list(p) for p in pts]



MAX_HULL_VERTICES = 128  # the 3-D model's bound on hull vertices (physics/base_body.hpp), base included


def contact_hull(points, base, contact_tolerance, max_vertices=MAX_HULL_VERTICES):
    """The hull key: the convex hull's vertices above the base patch (z > contact tolerance; the patch
    itself is base_polygon), floor frame, m. When there are more than the model takes beside the
    base, the hull of the support points in evenly spread directions (a Fibonacci sphere), as many
    directions as fit: an inscribed hull that touches the true one in every direction used."""
    from scipy.spatial import ConvexHull
    pts = np.asarray(points, dtype=float)
    verts = pts[ConvexHull(pts).vertices]
    verts = verts[verts[:, 2] > contact_tolerance]
    budget = max_vertices - len(base)
    if len(verts) <= budget:
        return sorted(verts.tolist())
    for k in range(4 * budget, 3, -1):
        i = np.arange(k) + 0.5
        z = 1.0 - 2.0 * i / k
        phi = math.pi * (1.0 + 5.0 ** 0.5) * i
        d = np.stack([np.sqrt(1.0 - z * z) * np.cos(phi), np.sqrt(1.0 - z * z) * np.sin(phi), z], axis=1)
        chosen = np.unique(np.argmax(verts @ d.T, axis=0))
        if len(chosen) <= budget:
            return sorted(verts[chosen].tolist())
    raise GeometryError("the hull cannot be simplified to the model's vertex bound")


# ---------------------------------------------------------------- one placed body
def fmt(x):
    return f"{x:.9g}"


def rocking_geometry(vertices, faces, rotation=np.eye(3), mass=1.0, contact_tolerance=1e-3,
                     com=None, settle_on_hull=False, com_shift=None):
    """All the quantities of the module docstring; `com` (mesh frame) overrides the homogeneous
    centre of mass (a specimen's measured one); the inertia stays the mesh's about that point.
    `com_shift` (dx, dy), m, floor frame: moves the centre of mass horizontally after placement and
    settling (the settled face stays the one found for the unshifted centre); the inertia again the
    mesh's about the moved point."""
    if not mass > 0:
        raise GeometryError(f"mass must be > 0 kg, got {mass}")
    if not contact_tolerance >= 0:
        raise GeometryError(f"contact tolerance must be >= 0 m, got {contact_tolerance}")
    volume, com_mesh, second = mass_properties(vertices, faces)
    inertia_mesh = central_inertia(volume, com_mesh, second, mass)
    if com is not None:
        d = np.asarray(com, dtype=float) - com_mesh
        inertia_mesh = inertia_mesh + mass * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
        com_mesh = np.asarray(com, dtype=float)
    settle_angle = 0.0
    if settle_on_hull:
        used0 = np.unique(faces)
        r, settle_angle = settle(vertices[used0] @ rotation.T, rotation @ com_mesh, contact_tolerance)
        rotation = r @ rotation
    placed = vertices @ rotation.T
    floor = placed[:, 2].min()
    placed = placed - np.array([0.0, 0.0, floor])  # floor at z = 0
    c = rotation @ com_mesh - np.array([0.0, 0.0, floor])
    inertia = rotation @ inertia_mesh @ rotation.T
    if com_shift is not None:
        d = np.array([com_shift[0], com_shift[1], 0.0], dtype=float)
        if not np.all(np.isfinite(d)):
            raise GeometryError(f"com shift must be finite, got {list(com_shift)}")
        inertia = inertia + mass * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
        c = c + d
    inertia = 0.5 * (inertia + inertia.T)  # exactly symmetric: the entry writes Ixy once for both
    used = np.unique(faces)
    low = placed[used]
    contact = low[low[:, 2] <= contact_tolerance]
    hull = convex_hull_2d(contact[:, :2])
    px, py = plane(contact, c, inertia, mass, 0), plane(contact, c, inertia, mass, 1)
    polygon = base_polygon(hull)
    # over both pivot pairs is not enough in 3-D: an oblique base can leave the centre outside
    if not point_in_convex(np.asarray(polygon), c[:2]):
        raise GeometryError(f"centre of mass (x, y = {c[0]:.6g}, {c[1]:.6g} m) is not over the base "
                            f"polygon: the placement is not at rest")
    result = {"volume": volume, "mass": mass, "density": mass / volume, "com": c.tolist(),
              "inertia": inertia.tolist(), "principal_inertia": sorted(np.linalg.eigvalsh(inertia).tolist()),
              "contact_points": int(len(contact)), "contact_tolerance": contact_tolerance,
              "settle_angle_deg": math.degrees(settle_angle), "rotation": rotation.tolist(),
              "hull": hull.tolist(), "base_polygon": polygon,
              "contact_hull": contact_hull(low, polygon, contact_tolerance), "com_shift": None if com_shift is None
              else [float(com_shift[0]), float(com_shift[1])], "x": px, "y": py}
    return result, placed
