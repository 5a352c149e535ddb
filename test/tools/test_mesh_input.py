#!/usr/bin/env python3
"""Scans to catalogue entries (issue 43): meshes made here with closed-form mass properties (a box, a
24-sided prism, an L turned about the vertical and moved) written in PLY, STL, OBJ, OFF and GLB, in
metres and millimetres, closed and open at the base, give entries equal to the closed forms to 1e-6
relative; a scanned floor or turntable is removed; each bad mesh gets its one message; the granite
specimens written in every format give today's entries (test/tools/granite_specimens_3d.yaml; skipped
with a notice without ../shared).

  test_mesh_input.py [GRANITE_PBR_DIR]
"""
import math
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np
import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.join(HERE, "..", "..", "scripts")
sys.path.insert(0, SCRIPTS)
import meshio  # noqa: E402
import rocking_geometry as rg  # noqa: E402
import scan_entry  # noqa: E402

GRANITE_DIR = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(HERE, "..", "..", "..", "shared",
                                                                       "experiments", "granite_pbr")
REL = 1e-6
FORMATS = ["ply", "stl", "obj", "off", "glb"]


# ---------------------------------------------------------------- meshes with closed forms

def prism(polygon, height, z0=0.0):
    """A right prism over a counter-clockwise polygon that is star-shaped from its vertex 0 (fanned
    from it): vertices, triangles (outward), and the bottom cap's triangle indices."""
    n = len(polygon)
    v = [[x, y, z0] for x, y in polygon] + [[x, y, z0 + height] for x, y in polygon]
    bottom = [(0, k + 1, k) for k in range(1, n - 1)]
    top = [(n, n + k, n + k + 1) for k in range(1, n - 1)]
    sides = []
    for k in range(n):
        a, b = k, (k + 1) % n
        sides += [(a, b, n + b), (a, n + b, n + a)]
    f = np.array(bottom + top + sides)
    return np.array(v, float), f, np.arange(len(bottom))


def box_closed_form(a, b, c, m, corner=(0, 0, 0)):
    com = np.array(corner, float) + [a / 2, b / 2, c / 2]
    inertia = np.diag([m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12])
    return com, inertia


def shifted(inertia, m, d):
    d = np.asarray(d, float)
    return inertia + m * (np.dot(d, d) * np.eye(3) - np.outer(d, d))


def case_box():
    a, b, c, m = 0.9, 0.4, 1.8, 80.0
    v, f, bottom = prism([(0, 0), (a, 0), (a, b), (0, b)], c)
    com, inertia = box_closed_form(a, b, c, m)
    return v, f, bottom, m, com, inertia, [(0, 0), (a, 0), (a, b), (0, b)]


def case_cylinder(n=24, r=0.2, h=0.7, m=30.0):
    """A regular n-gon prism: J = A R^2 (2 + cos(2 pi / n)) / 6 about its axis (R circumradius: n
    triangles from the centre, each A_t / 6 (|a|^2 + |b|^2 + a.b))."""
    poly = [(r * math.cos(2 * math.pi * k / n), r * math.sin(2 * math.pi * k / n)) for k in range(n)]
    v, f, bottom = prism(poly, h)
    izz = m * r * r * (2 + math.cos(2 * math.pi / n)) / 6
    ixx = izz / 2 + m * h * h / 12
    return v, f, bottom, m, np.array([0, 0, h / 2]), np.diag([ixx, ixx, izz]), poly


def case_l(yaw_deg=35.0, move=(0.3, -0.2, 0.15)):
    """An L (two boxes) turned by yaw about the vertical and moved: the floor is found again."""
    a, b, t, h, rho = 0.6, 0.5, 0.2, 1.2, 500.0
    poly = [(0, 0), (a, 0), (a, t), (t, t), (t, b), (0, b)]
    v, f, bottom = prism(poly, h)
    parts = [((0, 0, 0), (a, t, h)), ((0, t, 0), (t, b - t, h))]
    m = sum(rho * p[1][0] * p[1][1] * p[1][2] for p in parts)
    com = sum(rho * np.prod(s) * (np.array(c0) + np.array(s) / 2) for c0, s in parts) / m
    inertia = np.zeros((3, 3))
    for c0, s in parts:
        mi = rho * np.prod(s)
        ci, ii = box_closed_form(*s, mi, c0)
        inertia += shifted(ii, mi, ci - com)
    q = math.radians(yaw_deg)
    r = np.array([[math.cos(q), -math.sin(q), 0], [math.sin(q), math.cos(q), 0], [0, 0, 1]])
    v = v @ r.T + np.array(move)
    com = r @ com + np.array(move)
    hull = [(a, t), (t, b), (0, b), (0, 0), (a, 0)]  # (t, t) is the re-entrant corner
    hull = [tuple(r[:2, :2] @ p + move[:2]) for p in hull]
    return v, f, bottom, m, com, r @ inertia @ r.T, hull


CASES = {"box": case_box, "cylinder": case_cylinder, "L": case_l}


def expected_entry(m, com, inertia, hull):
    """The entry's keys from the closed form (rocking_geometry's module docstring defines them)."""
    hull = np.array(hull)
    lo, hi = hull.min(axis=0), hull.max(axis=0)
    return {"width": hi[0] - lo[0], "depth": hi[1] - lo[1], "cg_height": com[2],
            "eccentricity": (com[0] - lo[0]) / (hi[0] - lo[0]),
            "eccentricity_y": (com[1] - lo[1]) / (hi[1] - lo[1]),
            "radius_of_gyration": math.sqrt(inertia[1, 1] / m),
            "radius_of_gyration_y": math.sqrt(inertia[0, 0] / m),
            "mass": m, "centre_of_mass": list(com), "central_inertia": inertia.tolist(),
            "base_polygon": hull.tolist()}


def write(path, v, f, fmt, y_up=False):
    """The mesh in a format, through meshio (GLB: meshio's PLY through assimp's exporter, stored y-up
    as glTF specifies)."""
    if y_up:
        v = v @ np.array([[1, 0, 0], [0, 0, 1], [0, -1, 0]], float).T  # z up -> y up
    if fmt == "glb":
        ply = path[:-4] + "_for_glb.ply"
        meshio.Mesh(v, [("triangle", f.astype(np.int32))]).write(ply)
        r = subprocess.run(["assimp", "export", ply, path], capture_output=True, text=True)
        assert r.returncode == 0, r.stdout + r.stderr
    else:
        meshio.Mesh(v, [("triangle", f.astype(np.int32))]).write(path, file_format=fmt)
    return path


def entry_of(path, m, **kw):
    g, _, notes = scan_entry.scan_geometry(path, m, 1e-3, **kw)
    return yaml.safe_load("items:\n" + rg.catalogue_entry("x", g))["items"][0], notes


class Close:
    def assertRel(self, got, want, rel=REL, what=""):
        got, want = np.asarray(got, float), np.asarray(want, float)
        scale = max(float(np.max(np.abs(want))), 1e-300)
        self.assertTrue(got.shape == want.shape and np.all(np.abs(got - want) <= rel * scale),
                        f"{what}\n got {got}\nwant {want}")

    def assertEntry(self, got, want, what):
        for k, w in want.items():
            if k == "base_polygon":  # the same vertices, counter-clockwise, any starting vertex
                g = np.array(got[k])
                self.assertEqual(len(g), len(w), f"{what}: base_polygon {g}")
                start = int(np.argmin(np.linalg.norm(g - np.array(w[0]), axis=1)))
                self.assertRel(np.roll(g, -start, axis=0), w, what=f"{what}: base_polygon")
            else:
                self.assertRel(got[k], w, what=f"{what}: {k}")


class ClosedForms(unittest.TestCase, Close):
    """Every case x format x unit x open/closed equals its closed form."""

    def test_cases(self):
        with tempfile.TemporaryDirectory() as tmp:
            for name, make in CASES.items():
                v, f, bottom, m, com, inertia, hull = make()
                want = expected_entry(m, com - [0, 0, v[:, 2].min()], inertia, hull)
                for opened in (False, True):
                    faces = np.delete(f, bottom, axis=0) if opened else f
                    for unit, scale in (("m", 1.0), ("mm", 1000.0)):
                        for fmt in FORMATS:
                            what = f"{name} {fmt} {unit} {'open' if opened else 'closed'}"
                            path = write(os.path.join(tmp, f"{name}_{unit}_{opened}.{fmt}"), v * scale,
                                         faces, fmt, y_up=fmt == "glb")
                            got, notes = entry_of(path, m)
                            self.assertEntry(got, want, what)
                            self.assertIn(f"unit {unit} (largest extent", notes[1], what)
                            self.assertEqual(any("capped" in n for n in notes), opened, what)

    def test_stated_unit_overrides(self):
        with tempfile.TemporaryDirectory() as tmp:
            v, f, _, m, com, inertia, hull = case_box()
            path = write(os.path.join(tmp, "b.ply"), v * 100, f, "ply")  # centimetres: 180 units tall
            got, notes = entry_of(path, m, unit="cm")
            self.assertEntry(got, expected_entry(m, com, inertia, hull), "cm")
            self.assertIn("unit cm (--unit)", notes)

    def test_lying_scan_stood_up(self):
        # the box scanned lying on its back, its up axis x: --up x stands it on its base again
        with tempfile.TemporaryDirectory() as tmp:
            v, f, _, m, com, inertia, hull = case_box()
            turn = np.array([[0, 0, 1], [0, 1, 0], [-1, 0, 0]], float)  # z -> x
            path = write(os.path.join(tmp, "lying.off"), v @ turn.T, f, "off")
            got, _ = entry_of(path, m, up="x")
            for k in ("cg_height", "mass"):
                self.assertRel(got[k], expected_entry(m, com, inertia, hull)[k], what=k)
            self.assertRel(sorted(np.linalg.eigvalsh(got["central_inertia"])), sorted(np.diag(inertia)))

    def test_largest_face(self):
        with tempfile.TemporaryDirectory() as tmp:
            v, f, _, m, com, inertia, hull = case_box()
            path = write(os.path.join(tmp, "b.obj"), v, f, "obj")
            got, notes = entry_of(path, m, floor="largest")
            self.assertRel(got["cg_height"], 0.2, what="on its 0.9 x 1.8 m side")  # half the 0.4 m depth
            self.assertTrue(any("largest convex-hull face" in n and "1.62 m^2" in n for n in notes), notes)

    def test_cli_states_unit_and_writes_the_hull_by_default(self):
        with tempfile.TemporaryDirectory() as tmp:
            v, f, bottom, m, *_ = case_cylinder()
            path = write(os.path.join(tmp, "c.stl"), v * 1000, np.delete(f, bottom, axis=0), "stl")
            r = subprocess.run([sys.executable, os.path.join(SCRIPTS, "rocking_geometry.py"), path,
                                "--mass", str(m), "--write-hull"], capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("unit mm (largest extent 700", r.stderr)
            self.assertIn("open: 1 hole(s), 24 boundary edges, each capped", r.stderr)
            item = yaml.safe_load(r.stdout)["items"][0]
            # the hull above the base: the top rim's 24 points (the bottom rim is base_polygon)
            self.assertEqual(len(item["hull"]), 24)
            self.assertEqual(len(item["base_polygon"]), 24)
            for p in item["hull"]:
                self.assertRel(p[2], 0.7)
            r = subprocess.run([sys.executable, os.path.join(SCRIPTS, "rocking_geometry.py"), path,
                                "--mass", str(m), "--no-hull"], capture_output=True, text=True)
            self.assertNotIn("hull", yaml.safe_load(r.stdout)["items"][0])


class Slab(unittest.TestCase, Close):
    def test_turntable_and_floor_patch_removed(self):
        v, f, bottom, m, com, inertia, hull = case_box()
        obj_v, obj_f = v * 0.3, np.delete(f, bottom, axis=0)  # 270 x 120 x 540 mm, open at its base
        want = expected_entry(m, com * 0.3, inertia * 0.09, np.array(hull) * 0.3)
        slab_v, slab_f, _ = prism([(-0.4, -0.4), (0.6, -0.4), (0.6, 0.6), (-0.4, 0.6)], 0.02)
        patch_v = np.array([[-0.5, -0.5, 0], [0.8, -0.5, 0], [0.8, 0.7, 0], [-0.5, 0.7, 0]])
        with tempfile.TemporaryDirectory() as tmp:
            for name, (sv, sf, lift) in {"turntable": (slab_v, slab_f, 0.02),
                                         "floor patch": (patch_v, np.array([[0, 1, 2], [0, 2, 3]]), 0.0)}.items():
                allv = np.vstack([sv, obj_v + [0, 0, lift]])
                allf = np.vstack([sf, obj_f + len(sv)])
                path = write(os.path.join(tmp, "s.ply"), allv, allf, "ply")
                got, notes = entry_of(path, m)
                self.assertEntry(got, want, name)
                self.assertTrue(any(n.startswith("floor or turntable slab removed") for n in notes), notes)
                if name == "turntable":  # kept: the object's open base is 20 mm above the floor
                    with self.assertRaises(rg.GeometryError):
                        entry_of(path, m, keep_slab=True)
                else:  # kept: the patch is part of the body, the base is the patch's 1.3 x 1.2 m
                    self.assertRel(entry_of(path, m, keep_slab=True)[0]["width"], 1.3)

    def test_none_recognised_is_stated(self):
        v, f, _, m, *_ = case_cylinder()
        with tempfile.TemporaryDirectory() as tmp:
            _, notes = entry_of(write(os.path.join(tmp, "c.ply"), v, f, "ply"), m)
            self.assertTrue(any("slab: none recognised" in n for n in notes), notes)


class BadMeshes(unittest.TestCase):
    """One clear message per kind of bad input."""

    def refused(self, name, data, message, binary=False, **kw):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, name)
            if isinstance(data, tuple):
                write(path, data[0], data[1], name.rsplit(".", 1)[1])
            else:
                with open(path, "wb" if binary else "w") as out:
                    out.write(data)
            with self.assertRaises(rg.GeometryError) as e:
                scan_entry.scan_geometry(path, 1.0, **kw)
            self.assertIn(message, str(e.exception))
            self.assertIn(path, str(e.exception))  # names the file
            return str(e.exception)

    def test_each_class(self):
        v, f, bottom, *_ = case_box()
        self.refused("e.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "no triangles (a point cloud)")
        self.refused("e.off", "OFF\n0 0 0\n", "no triangles (empty)")
        self.refused("g.ply", b"\x00\x01garbage\xff" * 20, "not a readable PLY mesh", binary=True)
        self.refused("g.xyz", "1 2 3\n", "unknown mesh format '.xyz'")
        line = np.array([[0, 0, 0], [0.5, 0, 0], [1, 0, 0], [0.2, 0, 0]], float)
        self.refused("line.ply", (line, np.array([[0, 1, 2], [0, 3, 1]])), "degenerate: every triangle has zero area")
        flat = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0.25, 0.25, 0]], float)  # a pressed tetrahedron
        self.refused("flat.ply", (flat, np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])),
                     "degenerate: encloses 0 m^3")
        fin_v = np.vstack([v, [[0.45, -0.5, 0.9]]])
        self.refused("fin.ply", (fin_v, np.vstack([f, [[0, 1, 8]]])), "non-manifold")
        flipped = f.copy()
        flipped[5] = flipped[5, ::-1]
        self.refused("flip.obj", (v, flipped), "traversed twice in the same direction")
        two = (np.vstack([v, v + [0.3, 0.1, 0.5]]), np.vstack([f, f + 8]))
        self.refused("two.stl", two, "self-intersecting: ")
        self.refused("huge.ply", (v * 30, f), "absurd size: largest extent 54 m", unit="m")
        self.refused("tiny.ply", (v * 1e-3, f), "absurd size", unit="m")
        top = np.array([k for k in range(len(f)) if v[f[k], 2].min() > 1.7])
        self.refused("top.obj", (v, np.delete(f, top, axis=0)),
                     "open elsewhere than at its base: a hole of 4 edges reaches 1800 mm")


@unittest.skipUnless(os.path.isdir(GRANITE_DIR), f"{GRANITE_DIR} absent (../shared): granite cases skipped")
class Granite(unittest.TestCase, Close):
    """The specimens written in each format give today's entries (the 3-D catalogue the experiments use)."""

    def test_formats(self):
        with open(os.path.join(HERE, "granite_specimens_3d.yaml")) as f:
            today = {it["id"]: it for it in yaml.safe_load(f)["items"]}
        with tempfile.TemporaryDirectory() as tmp:
            for name, spec in rg.GRANITE.items():
                v, f = rg.read_obj(os.path.join(GRANITE_DIR, spec["mesh"]))
                for fmt in FORMATS:
                    path = write(os.path.join(tmp, f"{name}.{fmt}"), v, f, fmt)
                    g, _, _ = scan_entry.scan_geometry(path, spec["mass"], 1e-3, spec["com"], unit="m",
                                                       quaternion=spec["quaternion"], settle=True,
                                                       keep_slab=True)
                    got = yaml.safe_load("items:\n" + rg.catalogue_entry(name, g))["items"][0]
                    exact = fmt in ("ply", "off", "obj")  # doubles; STL and glTF store 32-bit floats
                    for k, w in today[name].items():
                        if isinstance(w, str):
                            continue
                        if exact:
                            self.assertEqual(got[k], w, f"{name} {fmt} {k}")
                        else:
                            self.assertRel(got[k], w, rel=1e-6, what=f"{name} {fmt} {k}")


if __name__ == "__main__":
    if not os.path.isdir(GRANITE_DIR):
        print(f"notice: {GRANITE_DIR} absent: the granite cases are skipped")
    unittest.main(verbosity=2)
