#!/usr/bin/env python3
"""rocking_geometry on closed forms: a box, a box with an off-centre hollow, a box turned about the
vertical (pivots at its corners) give the analytic centre of mass, inertia and per-pivot alpha, R;
the catalogue entry's 3-D keys (mass, centre_of_mass, base_polygon, central_inertia) parse as YAML
with the closed-form values, and --com-shift moves the centre of mass with the parallel-axis inertia."""
import gzip
import math
import os
import sys
import tempfile
import unittest

import numpy as np
import yaml

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


def ccw_rotation_of(got, want):
    """got is want (a counter-clockwise vertex list) up to where the cycle starts."""
    got, want = [tuple(p) for p in got], [tuple(p) for p in want]
    if len(got) != len(want):
        return False
    for s in range(len(want)):
        if all(np.allclose(got[k], want[(s + k) % len(want)], rtol=0, atol=1e-9) for k in range(len(want))):
            return True
    return False


def entry_keys(g, **kw):
    """The catalogue entry of g, parsed back by a YAML reader."""
    doc = yaml.safe_load("items:\n" + rg.catalogue_entry("box", g, **kw))
    return doc["items"][0]


class Test3dKeys(unittest.TestCase, Close):
    a, b, c, m = 0.4, 0.3, 1.2, 80.0

    def test_box_corners_centre_inertia(self):
        x0, y0 = -0.1, 0.2
        v, f = box((x0, y0, 0.0), (x0 + self.a, y0 + self.b, self.c))
        g, _ = rg.rocking_geometry(v, f, np.eye(3), self.m, 1e-6)
        corners = [(x0, y0), (x0 + self.a, y0), (x0 + self.a, y0 + self.b), (x0, y0 + self.b)]  # CCW
        self.assertTrue(ccw_rotation_of(g["base_polygon"], corners), g["base_polygon"])
        e = entry_keys(g)
        self.assertEqual(e["mass"], self.m)
        self.assertEqual(len(e["centre_of_mass"]), 3)
        self.assertRel(e["centre_of_mass"], [x0 + self.a / 2, y0 + self.b / 2, self.c / 2], 1e-8)
        self.assertEqual([len(p) for p in e["base_polygon"]], [2, 2, 2, 2])
        self.assertTrue(ccw_rotation_of(e["base_polygon"], corners), e["base_polygon"])
        self.assertEqual([len(r) for r in e["central_inertia"]], [3, 3, 3])
        self.assertRel(e["central_inertia"], box_inertia(self.m, self.a, self.b, self.c), 1e-8)
        # the planar keys are still there, unchanged
        self.assertRel(e["width"], self.a, 1e-8)
        self.assertRel(e["depth"], self.b, 1e-8)
        p = entry_keys(g, planar_only=True)
        for key in ("mass", "centre_of_mass", "base_polygon", "central_inertia"):
            self.assertNotIn(key, p)
        self.assertRel(p["cg_height"], self.c / 2, 1e-8)

    def test_box_turned_about_vertical_has_off_diagonal_inertia(self):
        a, b, c, m, psi = 0.6, 0.2, 0.9, 50.0, math.radians(30.0)
        v, f = box((-a / 2, -b / 2, 0.0), (a / 2, b / 2, c))
        q = (0.0, 0.0, math.sin(psi / 2), math.cos(psi / 2))
        g, _ = rg.rocking_geometry(v, f, rg.quaternion_matrix(*q), m, 1e-6)
        e = entry_keys(g)
        cs, sn = math.cos(psi), math.sin(psi)
        ib = box_inertia(m, a, b, c)
        ixy = sn * cs * (ib[0, 0] - ib[1, 1])  # R diag R^T, R about z by psi
        self.assertGreater(abs(ixy), 0.5)  # a real off-diagonal term, kg m^2
        want = [[cs * cs * ib[0, 0] + sn * sn * ib[1, 1], ixy, 0.0],
                [ixy, sn * sn * ib[0, 0] + cs * cs * ib[1, 1], 0.0],
                [0.0, 0.0, ib[2, 2]]]
        self.assertRel(e["central_inertia"], want, 1e-8)
        self.assertEqual(e["central_inertia"][0][1], e["central_inertia"][1][0])
        corners = [(-a / 2, -b / 2), (a / 2, -b / 2), (a / 2, b / 2), (-a / 2, b / 2)]
        turned = [(cs * x - sn * y, sn * x + cs * y) for x, y in corners]
        self.assertTrue(ccw_rotation_of(e["base_polygon"], turned), e["base_polygon"])
        self.assertRel(e["centre_of_mass"], [0.0, 0.0, c / 2], 1e-8)

    def test_collinear_and_duplicate_base_vertices_are_dropped(self):
        # a box whose bottom and top faces are 2 x 2 grids: 9 contact vertices (edge midpoints and
        # the centre collinear with the corners), the base polygon is the 4 corners
        a, b, c = 0.4, 0.2, 0.5
        xs, ys = (0.0, a / 2, a), (0.0, b / 2, b)
        v = [[xs[i], ys[j], z] for z in (0.0, c) for j in range(3) for i in range(3)]
        n = lambda i, j, top=0: 3 * j + i + 9 * top  # noqa: E731
        f = []
        for i in range(2):
            for j in range(2):
                f += [(n(i, j), n(i + 1, j + 1), n(i + 1, j)), (n(i, j), n(i, j + 1), n(i + 1, j + 1))]  # down
                f += [(n(i, j, 1), n(i + 1, j, 1), n(i + 1, j + 1, 1)), (n(i, j, 1), n(i + 1, j + 1, 1), n(i, j + 1, 1))]
        ring = [(0, 0), (1, 0), (2, 0), (2, 1), (2, 2), (1, 2), (0, 2), (0, 1)]  # CCW from above
        for k in range(8):  # side quads p, q, Q, P: outward for a counter-clockwise ring
            p, q = ring[k], ring[(k + 1) % 8]
            f += [(n(*p), n(*q), n(*q, 1)), (n(*p), n(*q, 1), n(*p, 1))]
        v, f = np.array(v, dtype=float), np.array(f)
        self.assertEqual(rg.open_edges(v, f), 0)
        g, _ = rg.rocking_geometry(v, f, np.eye(3), 1.0, 1e-6)
        self.assertEqual(g["contact_points"], 9)
        self.assertRel(g["volume"], a * b * c)
        self.assertTrue(ccw_rotation_of(g["base_polygon"], [(0, 0), (a, 0), (a, b), (0, b)]), g["base_polygon"])

    def test_base_polygon_drops_near_collinear_keeps_real_corners(self):
        square = [(0, 0), (0.3, 0), (0.3, 0.3), (0, 0.3)]
        # 0.1 um outward of an edge: within the tolerance, dropped; 10 um: a real vertex, kept
        self.assertEqual(len(rg.base_polygon(square + [(0.15, -1e-7), (0.0, 0.0)])), 4)
        kept = rg.base_polygon(square + [(0.15, -1e-5)])
        self.assertEqual(len(kept), 5)
        self.assertIn([0.15, -1e-5], kept)
        area2 = sum(kept[k - 1][0] * kept[k][1] - kept[k][0] * kept[k - 1][1] for k in range(len(kept)))
        self.assertGreater(area2, 0)  # counter-clockwise
        with self.assertRaisesRegex(rg.GeometryError, "vertices after dropping collinear"):
            rg.base_polygon([(0, 0), (0.1, 0.1), (0.2, 0.2 + 1e-8)])

    def test_base_polygon_keeps_at_most_64_vertices(self):
        n, r = 200, 0.2
        circle = [(r * math.cos(2 * math.pi * k / n), r * math.sin(2 * math.pi * k / n)) for k in range(n)]
        poly = rg.base_polygon(circle)
        self.assertEqual(len(poly), 64)
        area = 0.5 * sum(poly[k - 1][0] * poly[k][1] - poly[k][0] * poly[k - 1][1] for k in range(64))
        full = 0.5 * n * r * r * math.sin(2 * math.pi / n)
        self.assertGreater(area, 0.99 * full)  # a round base loses < 1 % of its area
        self.assertLess(area, full)
        for k in range(64):  # still strictly convex counter-clockwise
            (ax, ay), (bx, by), (cx, cy) = poly[k - 2], poly[k - 1], poly[k]
            self.assertGreater((bx - ax) * (cy - ay) - (by - ay) * (cx - ax), 0)

    def test_com_shift_moves_centre_with_parallel_axis_inertia(self):
        a, b, c, m, dx, dy = 0.4, 0.3, 1.0, 20.0, 0.03, -0.02
        v, f = box((-a / 2, -b / 2, 0.0), (a / 2, b / 2, c))
        g, _ = rg.rocking_geometry(v, f, np.eye(3), m, 1e-6, com_shift=(dx, dy))
        self.assertRel(g["com"], [dx, dy, c / 2])
        self.assertRel(g["inertia"], shifted(box_inertia(m, a, b, c), m, (dx, dy, 0.0)))
        self.assertRel(g["x"]["eccentricity"], (a / 2 + dx) / a)
        self.assertRel(g["y"]["eccentricity"], (b / 2 + dy) / b)
        self.assertRel(g["x"]["pivots"][1]["alpha"], math.atan2(a / 2 - dx, c / 2))
        e = entry_keys(g)
        self.assertRel(e["centre_of_mass"], [dx, dy, c / 2], 1e-8)

    def test_com_shifted_off_an_oblique_base_is_refused(self):
        # square turned 45 deg: a diamond |x| + |y| <= d; (0.8 d, 0.8 d) lies within both pivot pairs
        s = 0.3
        v, f = box((-s / 2, -s / 2, 0.0), (s / 2, s / 2, 1.0))
        q = (0.0, 0.0, math.sin(math.pi / 8), math.cos(math.pi / 8))
        d = s / math.sqrt(2)
        with self.assertRaisesRegex(rg.GeometryError, "not over the base polygon"):
            rg.rocking_geometry(v, f, rg.quaternion_matrix(*q), 1.0, 1e-6, com_shift=(0.8 * d, 0.8 * d))
        g, _ = rg.rocking_geometry(v, f, rg.quaternion_matrix(*q), 1.0, 1e-6, com_shift=(0.4 * d, 0.4 * d))
        self.assertEqual(len(g["base_polygon"]), 4)


class TestCommandLine(unittest.TestCase, Close):
    def write_box(self, d, a, b, c):
        v, f = box((-a / 2, -b / 2, 0.0), (a / 2, b / 2, c))
        path = os.path.join(d, "box.obj")
        with open(path, "w") as out:
            out.writelines("v %.17g %.17g %.17g\n" % tuple(p) for p in v)
            out.writelines("f %d %d %d\n" % tuple(t + 1) for t in f)
        return path

    def test_yaml_with_com_shift_and_planar_only(self):
        a, b, c, m = 0.4, 0.3, 1.0, 20.0
        with tempfile.TemporaryDirectory() as d:
            mesh = self.write_box(d, a, b, c)
            out = os.path.join(d, "cat.yaml")
            self.assertEqual(rg.main([mesh, "--mass", str(m), "--contact-tolerance", "1e-6",
                                      "--com-shift", "0.01", "0.02", "--yaml", out]), 0)
            with open(out) as fh:
                text = fh.read()
            self.assertIn("# made by: rocking_geometry.py", text)
            e = yaml.safe_load(text)["items"][0]
            self.assertRel(e["centre_of_mass"], [0.01, 0.02, c / 2], 1e-8)
            self.assertRel(e["central_inertia"], shifted(box_inertia(m, a, b, c), m, (0.01, 0.02, 0)), 1e-8)
            self.assertRel(e["eccentricity"], (a / 2 + 0.01) / a, 1e-8)
            self.assertEqual(rg.main([mesh, "--planar-only", "--yaml", out]), 0)
            with open(out) as fh:
                self.assertNotIn("centre_of_mass", yaml.safe_load(fh)["items"][0])
            # the shift pushes the centre past pivot 2: refused with the reason, exit 2
            self.assertEqual(rg.main([mesh, "--com-shift", "0.3", "0", "--yaml", out]), 2)
            self.assertEqual(rg.main([mesh, "--homogeneous", "--yaml", out]), 2)  # needs --granite


if __name__ == "__main__":
    unittest.main()
