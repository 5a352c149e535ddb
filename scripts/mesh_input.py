"""mesh_input: a scan or a CAD mesh as rocking_geometry.py needs it (issue 43).

Reads PLY, STL, OBJ and OFF through meshio (Debian python3-meshio) and glTF/GLB through assimp's
command-line tool (Debian assimp-utils: `assimp export` to PLY, node transforms applied, then
meshio), any of them optionally gzipped; no parser of our own. Then, in the file's frame:
  - the unit (m, or mm when the largest extent exceeds MM_ABOVE; --unit overrides), stated;
  - one clear error for each kind of bad mesh: unreadable, empty or a point cloud, degenerate (no
    volume), not a solid (an edge of more than two triangles, faces turned inconsistently, a boundary
    that is not a simple loop), self-intersecting, an absurd size;
  - a scanned floor or turntable slab recognised and removed (or the statement that none was);
  - the open boundary loops (a scan is usually open at its base), capped with a fan: the caps close
    the surface exactly for the volume integrals; rocking_geometry.py refuses the mesh when a capped
    hole is not at the floor it stands on (check_caps).
"""
import gzip
import os
import shutil
import subprocess
import tempfile

import numpy as np


class GeometryError(Exception):
    """Bad mesh or placement; the message names the file (and line) or the quantity."""


FORMATS = {".ply": "ply", ".stl": "stl", ".obj": "obj", ".off": "off", ".gltf": "gltf", ".glb": "gltf"}
UNITS = {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "in": 0.0254}
# A file whose largest extent exceeds this many of its units is read as millimetres: no free-standing
# item is 10 m long, and few are under 10 mm.
MM_ABOVE = 10.0
# Sizes outside this range (m) are not a free-standing item: a wrong unit, or a broken export.
SIZE_RANGE = (0.005, 20.0)


def _meshio():
    try:
        import meshio
    except ImportError:
        raise GeometryError("python3-meshio is not installed (apt-get install python3-meshio)")
    return meshio


def _via_assimp(src, tmp):
    """glTF/GLB to PLY with the scene graph's transforms applied (-ptv)."""
    tool = shutil.which("assimp")
    if not tool:
        raise GeometryError(f"{src}: glTF/GLB needs assimp's tool (apt-get install assimp-utils)")
    out = os.path.join(tmp, "converted.ply")
    run = subprocess.run([tool, "export", src, out, "-fplyb", "-ptv"], capture_output=True, text=True)
    if run.returncode != 0 or not os.path.isfile(out):
        last = [ln for ln in (run.stdout + run.stderr).splitlines() if ln.strip()][-1:] or ["no output"]
        raise GeometryError(f"{src}: assimp cannot read it as glTF ({last[0].strip()})")
    return out


def _without_obj_attributes(src, tmp):
    """A copy without normals (vn) and texture coordinates (vt): meshio 5's OBJ reader takes them for
    per-point data and refuses a file with more normals than points, which is valid OBJ (normals are
    per corner). The geometry does not need them."""
    out = os.path.join(tmp, "geometry.obj")
    try:
        with open(src, "rb") as fin, open(out, "wb") as fout:
            for line in fin:
                if not (line.startswith(b"vn") or line.startswith(b"vt")) or len(line) < 3 or line[2:3] not in b" \t":
                    fout.write(line)
    except OSError as e:
        raise GeometryError(f"{src}: cannot read ({e})")
    return out


def _ply_face_list_named(src, tmp):
    """meshio 5 reads a PLY face list only under the name vertex_indices; assimp and several scanners
    write vertex_index. A copy with the header's name changed (the body is untouched)."""
    try:
        with open(src, "rb") as fin:
            data = fin.read()
    except OSError as e:
        raise GeometryError(f"{src}: cannot read ({e})")
    end = data.find(b"end_header")
    head = data[:end]
    if end < 0 or b" vertex_index\n" not in head.replace(b"\r\n", b"\n"):
        return src
    out = os.path.join(tmp, "renamed.ply")
    with open(out, "wb") as fout:
        fout.write(head.replace(b" vertex_index\r\n", b" vertex_indices\r\n")
                   .replace(b" vertex_index\n", b" vertex_indices\n") + data[end:])
    return out


def read_mesh(path):
    """(vertices n x 3 float in the file's units, triangles m x 3 int, notes). Polygons are fanned;
    cells that are not surfaces (points, lines) are counted in the notes, not silently dropped."""
    name = path[:-3] if path.endswith(".gz") else path
    ext = os.path.splitext(name)[1].lower()
    if ext not in FORMATS:
        raise GeometryError(f"{path}: unknown mesh format '{ext or name}' (PLY, STL, OBJ, OFF, glTF or "
                            "GLB; .gz allowed)")
    if not os.path.isfile(path):
        raise GeometryError(f"{path}: cannot read (no such file)")
    meshio = _meshio()
    with tempfile.TemporaryDirectory() as tmp:
        src = path
        if path.endswith(".gz"):
            src = os.path.join(tmp, os.path.basename(name))
            try:
                with gzip.open(path, "rb") as fin, open(src, "wb") as fout:
                    shutil.copyfileobj(fin, fout)
            except (OSError, EOFError) as e:
                raise GeometryError(f"{path}: cannot decompress ({e})")
        fmt = FORMATS[ext]
        if fmt == "obj":
            src = _without_obj_attributes(src, tmp)
        if fmt == "gltf":
            src, fmt = _via_assimp(src, tmp), "ply"
        if fmt == "ply":
            src = _ply_face_list_named(src, tmp)
        try:
            mesh = meshio.read(src, file_format=fmt)
        except Exception as e:  # meshio raises ReadError, ValueError, IndexError, ... on bad files
            raise GeometryError(f"{path}: not a readable {ext[1:].upper()} mesh "
                                f"({type(e).__name__}: {str(e).strip()[:200] or 'no detail'})")
    vertices = np.asarray(mesh.points, dtype=float)
    if vertices.ndim != 2 or vertices.shape[1] < 3:
        raise GeometryError(f"{path}: vertices are not 3-D")
    vertices = vertices[:, :3]
    triangles, skipped = [], {}
    for block in mesh.cells:
        data = np.asarray(block.data)
        if block.type == "triangle":
            triangles.append(data.reshape(-1, 3))
        elif block.type == "quad" or block.type.startswith("polygon"):
            data = data.reshape(len(data), -1)
            for k in range(1, data.shape[1] - 1):  # fan; per polygon order kept within each fan step
                triangles.append(data[:, [0, k, k + 1]])
        else:
            skipped[block.type] = skipped.get(block.type, 0) + len(data)
    notes = [f"{ext[1:].upper()} read by meshio" + (" after assimp" if FORMATS[ext] == "gltf" else "")]
    if skipped:
        notes.append("ignored, not surfaces: " + ", ".join(f"{n} {t} cells" for t, n in skipped.items()))
    if not triangles or not sum(len(t) for t in triangles):
        what = "a point cloud" if len(vertices) else "empty"
        raise GeometryError(f"{path}: no triangles ({what}): a solid needs a closed surface; mesh the "
                            "point cloud in the scanning software first")
    faces = np.concatenate(triangles).astype(np.int64)
    if faces.min() < 0 or faces.max() >= len(vertices):
        raise GeometryError(f"{path}: a face refers to vertex {int(faces.max())}, the file has "
                            f"{len(vertices)} vertices")
    if not np.all(np.isfinite(vertices[np.unique(faces)])):
        raise GeometryError(f"{path}: a vertex is not a finite number")
    return vertices, faces, notes


def unit_scale(vertices, faces, unit, path):
    """(scale to metres, note). unit: 'auto' or a key of UNITS. Refuses an absurd size."""
    used = vertices[np.unique(faces)]
    extent = float((used.max(axis=0) - used.min(axis=0)).max())
    if unit == "auto":
        unit = "mm" if extent > MM_ABOVE else "m"
        why = (f"largest extent {extent:.6g} file units > {MM_ABOVE:g}: read as mm" if unit == "mm" else
               f"largest extent {extent:.6g} file units <= {MM_ABOVE:g}: read as m")
        note = f"unit {unit} ({why}; --unit to override)"
    else:
        note = f"unit {unit} (--unit)"
    scale = UNITS[unit]
    size = extent * scale
    if not SIZE_RANGE[0] <= size <= SIZE_RANGE[1]:
        raise GeometryError(f"{path}: absurd size: largest extent {size:.6g} m read as {unit} (a "
                            f"free-standing item is {SIZE_RANGE[0] * 1000:g} mm to {SIZE_RANGE[1]:g} m); "
                            "is --unit right?")
    return scale, note


# ---------------------------------------------------------------- cleaning and topology

def merge_vertices(vertices, faces, tolerance):
    """Coincident vertices (within tolerance, m: scanner exports duplicate them per face) merged;
    triangles that collapse (a repeated vertex or zero area) dropped. Returns (v, f, dropped)."""
    used = np.unique(faces)
    key = np.round(vertices[used] / tolerance).astype(np.int64) if tolerance > 0 else vertices[used]
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    remap = np.zeros(len(vertices), dtype=np.int64)
    remap[used] = inverse.reshape(-1)
    v = vertices[used][first]
    f = remap[faces]
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    area2 = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    scale = float(np.ptp(v, axis=0).max()) if len(v) else 0.0
    keep = (f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 2] != f[:, 0]) & (area2 > 1e-12 * scale * scale)
    return v, f[keep], int((~keep).sum())


def edge_report(faces):
    """(non-manifold undirected edges, directed edges used twice, boundary directed edges k x 2)."""
    directed = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]).astype(np.int64)
    n = int(directed.max()) + 1
    key, rev = directed[:, 0] * n + directed[:, 1], directed[:, 1] * n + directed[:, 0]
    _, ucount = np.unique(np.minimum(key, rev), return_counts=True)
    _, dcount = np.unique(key, return_counts=True)
    boundary = directed[~np.isin(rev, key)]
    return int((ucount > 2).sum()), int((dcount > 1).sum()), boundary


def boundary_loops(boundary, path):
    """The open boundary as closed vertex loops, in the direction of the surface's edges."""
    nxt = {}
    for a, b in boundary.tolist():
        if a in nxt:
            raise GeometryError(f"{path}: not a solid: the open boundary touches itself at a vertex "
                                "(two holes meet, or a bow-tie): repair the mesh in the scanning software")
        nxt[a] = b
    loops, seen = [], set()
    for start in nxt:
        if start in seen:
            continue
        loop, v = [], start
        while v not in seen:
            seen.add(v)
            loop.append(v)
            v = nxt.get(v)
            if v is None:
                raise GeometryError(f"{path}: not a solid: an open boundary does not close")
        loops.append(loop)
    return loops


def cap_loops(vertices, faces, loops):
    """Each loop closed by a fan from its centroid, turned against the loop (so every boundary edge
    gets its twin). Returns (v, f, cap_faces index range start)."""
    v, extra = [vertices], []
    n = len(vertices)
    for loop in loops:
        v.append(vertices[loop].mean(axis=0)[None, :])
        for k in range(len(loop)):
            extra.append([n, loop[(k + 1) % len(loop)], loop[k]])
        n += 1
    if not extra:
        return vertices, faces
    return np.vstack(v), np.vstack([faces, np.asarray(extra, dtype=np.int64)])


def _candidate_pairs(lo, hi, max_pairs):
    """Pairs of triangles whose bounding boxes share a cell of a uniform grid (cell: the median box
    size), i < j, without repeats; None when there would be more than max_pairs."""
    ext = (hi - lo).max(axis=1)
    size = max(float(np.median(ext)), 1e-12 * float(ext.max()), 1e-300)
    origin = lo.min(axis=0)
    c0 = np.floor((lo - origin) / size).astype(np.int64)
    c1 = np.floor((hi - origin) / size).astype(np.int64)
    span = c1 - c0 + 1
    count = span.prod(axis=1)
    if count.sum() > max_pairs:
        return None
    tri = np.repeat(np.arange(len(lo)), count)
    k = np.arange(len(tri)) - np.repeat(np.cumsum(count) - count, count)
    nx, ny = span[tri, 0], span[tri, 1]
    cell = np.stack([c0[tri, 0] + k % nx, c0[tri, 1] + (k // nx) % ny, c0[tri, 2] + k // (nx * ny)], axis=1)
    dims = c1.max(axis=0) + 1
    key = (cell[:, 0] * dims[1] + cell[:, 1]) * dims[2] + cell[:, 2]
    order = np.lexsort((tri, key))
    key, tri = key[order], tri[order]
    found, total, d = [], 0, 1
    while d < len(key):
        same = key[:-d] == key[d:]
        if not same.any():
            break
        a, b = tri[:-d][same], tri[d:][same]
        found.append(np.minimum(a, b) * len(lo) + np.maximum(a, b))
        total += len(a)
        if total > max_pairs:
            return None
        d += 1
    pairs = np.unique(np.concatenate(found)) if found else np.zeros(0, dtype=np.int64)
    return np.stack([pairs // len(lo), pairs % len(lo)], axis=1)


def crossing_triangles(vertices, faces, max_pairs=30_000_000, chunk=400_000):
    """Pairs of triangles (no shared vertex) where an edge of one passes through the other's interior:
    a self-intersecting surface. Returns (count, an example (i, j, point)) or (None, None) when too
    many candidate pairs to check."""
    a, b, c = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
    lo, hi = np.minimum(np.minimum(a, b), c), np.maximum(np.maximum(a, b), c)
    pairs = _candidate_pairs(lo, hi, max_pairs)
    if pairs is None:
        return None, None
    tol = 1e-9 * float(np.ptp(vertices, axis=0).max())
    count, example = 0, None
    for start in range(0, len(pairs), chunk):
        i, j = pairs[start:start + chunk, 0], pairs[start:start + chunk, 1]
        keep = np.all(lo[i] <= hi[j] + tol, axis=1) & np.all(lo[j] <= hi[i] + tol, axis=1)
        i, j = i[keep], j[keep]
        keep = ~(faces[i][:, :, None] == faces[j][:, None, :]).any(axis=(1, 2))
        i, j = i[keep], j[keep]
        hit = np.zeros(len(i), dtype=bool)
        where = np.zeros((len(i), 3))
        for s, t in ((i, j), (j, i)):
            tri = [vertices[faces[t, k]] for k in range(3)]
            for e in range(3):
                p0, p1 = vertices[faces[s, e]], vertices[faces[s, (e + 1) % 3]]
                h, q = _segment_hits(p0, p1, *tri)
                where[h & ~hit] = q[h & ~hit]
                hit |= h
        if hit.any() and example is None:
            k = int(np.argmax(hit))
            example = (int(i[k]), int(j[k]), where[k])
        count += int(hit.sum())
    return count, example


def _segment_hits(p0, p1, a, b, c, eps=1e-9):
    """Moeller-Trumbore for segments p0-p1 against triangles abc, strictly inside both."""
    d, e1, e2 = p1 - p0, b - a, c - a
    h = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, h)
    ok = np.abs(det) > 1e-14 * np.linalg.norm(d, axis=1) * np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1)
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = p0 - a
    u = np.einsum("ij,ij->i", s, h) * inv
    q = np.cross(s, e1)
    w = np.einsum("ij,ij->i", d, q) * inv
    t = np.einsum("ij,ij->i", e2, q) * inv
    hit = ok & (u > eps) & (w > eps) & (u + w < 1 - eps) & (t > eps) & (t < 1 - eps)
    return hit, p0 + t[:, None] * d


def check_solid(vertices, faces, path):
    """One error per kind of bad surface; returns the open boundary loops."""
    bad_edges, twice, boundary = edge_report(faces)
    if bad_edges:
        raise GeometryError(f"{path}: not a solid: {bad_edges} edges are shared by more than two "
                            "triangles (non-manifold: fins, or pieces glued along an edge)")
    if twice:
        raise GeometryError(f"{path}: not a solid: {twice} edges are traversed twice in the same "
                            "direction (faces turned inconsistently; unify the normals in the scanning "
                            "software)")
    loops = boundary_loops(boundary, path)
    count, example = crossing_triangles(vertices, faces)
    if count:
        i, j, p = example
        raise GeometryError(f"{path}: self-intersecting: {count} pairs of triangles cross (e.g. "
                            f"triangles {i} and {j} near ({p[0]:.4g}, {p[1]:.4g}, {p[2]:.4g}) m)")
    return loops, count is None


# ---------------------------------------------------------------- floor slab

def find_slab(vertices, faces, up, min_ratio=2.0, max_thickness=0.1):
    """A scanned floor or turntable under the object, in the frame where `up` is up: a bottom layer
    (under max_thickness of the height) whose plan (convex hull area) is at least min_ratio times
    that of everything above it. Returns (faces to keep, note); keep is None when none recognised."""
    from scipy.spatial import ConvexHull
    from scipy.spatial import QhullError
    used = np.unique(faces)
    up = np.asarray(up, float) / np.linalg.norm(up)
    e1 = np.cross(up, [1.0, 0, 0] if abs(up[0]) < 0.9 else [0, 1.0, 0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(up, e1)
    z = vertices @ up
    plan = np.stack([vertices @ e1, vertices @ e2], axis=1)
    z0, height = z[used].min(), np.ptp(z[used])

    def area(idx):
        try:
            return ConvexHull(plan[idx]).volume if len(idx) >= 3 else 0.0
        except QhullError:
            return 0.0

    total = area(used)
    step = height / 400
    best = None
    for k in range(1, int(max_thickness * 400) + 1):
        top = z0 + k * step
        above = used[z[used] > top]
        below = used[z[used] <= top]
        if len(above) < 4 or len(below) < 3:
            continue
        a_above, a_below = area(above), area(below)
        if a_above > 0 and a_below >= min_ratio * a_above and a_below >= 0.9 * total:
            best = (top, a_above, a_below)
            break
    if best is None:
        return None, ("floor or turntable slab: none recognised (the bottom "
                      f"{max_thickness * 100:g} % of the height is not {min_ratio:g} times wider than the rest)")
    top, a_above, a_below = best
    # the slab: every triangle with no vertex above its top (the object's walls keep theirs)
    slab = np.all(z[faces] <= top + 1e-9 * height, axis=1)
    note = (f"floor or turntable slab removed: {int(slab.sum())} triangles up to {(top - z0) * 1000:.3g} "
            f"mm above the lowest point, plan {a_below:.4g} m^2 against the object's {a_above:.4g} m^2 "
            "(--keep-slab to keep it)")
    return ~slab, note
