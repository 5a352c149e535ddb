#!/usr/bin/env python3
"""rocking_geometry on closed forms: a box, a box with an off-centre hollow, a box turned about the
vertical (pivots at its corners) give the analytic centre of mass, inertia and per-pivot alpha, R."""
import gzip
import math
import os
import sys
import tempfile
import unittest

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import rocking_geometry as rg  # noqa: E402

REL = 1e-9


def box(lo, hi, outward=True):
    """Closed box mesh, 8 vertices and 12 triangles, outward normals (or inward for a hollow)."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = np.array([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                  [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]], dtype=float)
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    f = []
    for a, b, c, d in quads:
        f += [(a, b, c), (a, c, d)]
    f = np.array(f)
    if not outward:
        f = f[:, ::-1]
    return v, f


def box_inertia(m, a, b, c):
    return np.diag([m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12])


def shifted(inertia, m, d):
    d = np.asarray(d, dtype=float)
    return inertia + m * (np.dot(d, d) * np.eye(3) - np.outer(d, d))


class Close:
    def assertRel(self, got, want, rel=REL):
        got, want = np.asarray(got, dtype=float), np.asarray(want, dtype=float)
        scale = max(np.max(np.abs(want)), 1e-300)
        self.assertTrue(np.all(np.abs(got - want) <= rel * scale), f"\n got {got}\nwant {want}")


class TestBox(unittest.TestCase, Close):
    a, b, c, m = 0.4, 0.3, 1.2, 80.0

    def test_centre_inertia_pivots(self):
        v, f = box((-0.1, 0.2, 0.0), (-0.1 + self.a, 0.2 + self.b, self.c))
        g, _ = rg.rocking_geometry(v, f, np.eye(3), self.m, 1e-6)
        self.assertRel(g["volume"], self.a * self.b * self.c)
        self.assertRel(g["com"], [-0.1 + self.a / 2, 0.2 + self.b / 2, self.c / 2])
        self.assertRel(g["inertia"], box_inertia(self.m, self.a, self.b, self.c))
        self.assertEqual(g["contact_points"], 4)
        h = self.c / 2
        for plane, width, rot in (("x", self.a, 1), ("y", self.b, 0)):
            p = g[plane]
            self.assertRel(p["width"], width)
            self.assertRel(p["cg_height"], h)
            self.assertRel(p["eccentricity"], 0.5)
            i_c = box_inertia(self.m, self.a, self.b, self.c)[rot, rot]
            self.assertRel(p["radius_of_gyration"], math.sqrt(i_c / self.m))
            for piv in p["pivots"]:
                self.assertRel(piv["alpha"], math.atan(width / 2 / h))
                self.assertRel(piv["radius"], math.hypot(width / 2, h))
                # box about its base edge: m (width^2 + c^2) / 3
                self.assertRel(piv["inertia"], self.m * (width ** 2 + self.c ** 2) / 3)

    def test_orientation_and_gzip_do_not_matter(self):
        v, f = box((0, 0, 0), (self.a, self.b, self.c), outward=False)
        g, _ = rg.rocking_geometry(v, f, np.eye(3), self.m, 1e-6)
        self.assertRel(g["volume"], self.a * self.b * self.c)
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "box.obj.gz")
            with gzip.open(path, "wt") as out:
                out.write("o box\n")
                for p in v:
                    out.write("v %.17g %.17g %.17g\n" % tuple(p))
                for t in f:
                    out.write("f %d//1 %d//1 %d//1\n" % tuple(t + 1))
            v2, f2 = rg.read_obj(path)
            self.assertEqual(rg.open_edges(v2, f2), 0)
            self.assertEqual(rg.open_edges(v2, f2[1:]), 3)  # one triangle missing: 3 open edges
            g2, _ = rg.rocking_geometry(v2, f2, np.eye(3), self.m, 1e-6)
            self.assertRel(g2["inertia"], g["inertia"])


class TestHollowBox(unittest.TestCase, Close):
    def test_off_centre_hollow(self):
        a, b, c, m = 0.5, 0.4, 1.0, 100.0
        lo, hi = np.array([0.05, 0.1, 0.2]), np.array([0.2, 0.3, 0.6])  # the hollow, off-centre in x
        vo, fo = box((0, 0, 0), (a, b, c))
        vi, fi = box(lo, hi, outward=False)
        v = np.vstack([vo, vi])
        f = np.vstack([fo, fi + len(vo)])
        g, _ = rg.rocking_geometry(v, f, np.eye(3), m, 1e-6)
        vol_o, vol_i = a * b * c, np.prod(hi - lo)
        vol = vol_o - vol_i
        rho = m / vol
        c_o, c_i = np.array([a, b, c]) / 2, (lo + hi) / 2
        com = (vol_o * c_o - vol_i * c_i) / vol
        self.assertRel(g["volume"], vol)
        self.assertRel(g["com"], com)
        ii = box_inertia(rho * vol_o, a, b, c)
        ih = box_inertia(rho * vol_i, *(hi - lo))
        inertia = shifted(ii, rho * vol_o, c_o - com) - shifted(ih, rho * vol_i, c_i - com)
        self.assertRel(g["inertia"], inertia)
        x = g["x"]
        h = com[2]
        b1, b2 = com[0], a - com[0]
        self.assertGreater(b1, b2)  # mass moved toward +x: pivot 1 (at x = 0) is the stable side
        self.assertRel(x["eccentricity"], b1 / a)
        for piv, lever in zip(x["pivots"], (b1, b2)):
            self.assertRel(piv["alpha"], math.atan2(lever, h))
            self.assertRel(piv["radius"], math.hypot(lever, h))
            self.assertRel(piv["inertia"], inertia[1, 1] + m * (lever ** 2 + h ** 2))


class TestTurnedBox(unittest.TestCase, Close):
    def test_turned_about_vertical(self):
        a, b, c, m, psi = 0.6, 0.2, 0.9, 50.0, math.radians(30.0)
        v, f = box((-a / 2, -b / 2, 0.0), (a / 2, b / 2, c))
        q = (0.0, 0.0, math.sin(psi / 2), math.cos(psi / 2))
        g, _ = rg.rocking_geometry(v, f, rg.quaternion_matrix(*q), m, 1e-6)
        ib = box_inertia(m, a, b, c)
        r = np.array([[math.cos(psi), -math.sin(psi), 0], [math.sin(psi), math.cos(psi), 0], [0, 0, 1]])
        self.assertRel(g["inertia"], r @ ib @ r.T)
        self.assertRel(g["com"], [0, 0, c / 2])
        width = a * math.cos(psi) + b * math.sin(psi)  # the rectangle's extent along x
        x = g["x"]
        self.assertRel(x["width"], width)
        self.assertRel(x["eccentricity"], 0.5)
        i_yy = math.sin(psi) ** 2 * ib[0, 0] + math.cos(psi) ** 2 * ib[1, 1]
        self.assertRel(x["radius_of_gyration"], math.sqrt(i_yy / m))
        for piv in x["pivots"]:
            self.assertRel(piv["alpha"], math.atan2(width / 2, c / 2))
            self.assertRel(piv["radius"], math.hypot(width / 2, c / 2))
            self.assertRel(piv["inertia"], i_yy + m * ((width / 2) ** 2 + (c / 2) ** 2))

    def test_tilted_onto_an_edge_is_refused(self):
        # pitched about y: the lowest points form one edge along y, no extent along x
        v, f = box((-0.2, -0.1, 0.0), (0.2, 0.1, 1.0))
        t = math.radians(10.0)
        q = (0.0, math.sin(t / 2), 0.0, math.cos(t / 2))
        with self.assertRaisesRegex(rg.GeometryError, "no extent along x"):
            rg.rocking_geometry(v, f, rg.quaternion_matrix(*q), 1.0, 1e-6)

    def test_settle_turns_a_slightly_tilted_box_back_onto_its_base(self):
        a, b, c, m = 0.4, 0.3, 1.0, 10.0
        v, f = box((-a / 2, -b / 2, 0.0), (a / 2, b / 2, c))
        t = math.radians(2.0)
        q = (math.sin(t / 2) * 0.6, math.sin(t / 2) * 0.8, 0.0, math.cos(t / 2))
        g, _ = rg.rocking_geometry(v, f, rg.quaternion_matrix(*q), m, 1e-6, settle_on_hull=True)
        self.assertRel(g["settle_angle_deg"], 2.0)
        self.assertEqual(g["contact_points"], 4)
        self.assertRel(g["x"]["width"], a)
        self.assertRel(g["y"]["width"], b)
        self.assertRel(g["x"]["cg_height"], c / 2)
        self.assertRel(g["inertia"], box_inertia(m, a, b, c))

    def test_centre_of_mass_outside_the_base_is_refused(self):
        v, f = box((0, 0, 0), (0.2, 0.2, 1.0))
        with self.assertRaisesRegex(rg.GeometryError, "not over the base"):
            rg.rocking_geometry(v, f, np.eye(3), 1.0, 1e-6, com=(0.3, 0.1, 0.5))


if __name__ == "__main__":
    unittest.main()
