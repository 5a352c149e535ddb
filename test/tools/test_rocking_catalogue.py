#!/usr/bin/env python3
"""rocking_catalogue (issue 43): a 100-row inventory spreadsheet round-trips through the catalogue YAML
(read back by the node's own parser, catalogue_check --json); the parser's errors come back naming the
row and the column, and no file is written; `check` gives the closed forms of a homogeneous box
(alpha = atan(B/H), uplift g B/H, p^2 = 3g/4R, Housner's eta = 1 - 1.5 sin^2 alpha, eq. 1's
sqrt(8/3 g R (1 - cos alpha)) / cos alpha) and its floor plan; a row with a scan gets the 3-D keys.

  test_rocking_catalogue.py CATALOGUE_CHECK
"""
import csv
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import unittest

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "scripts", "rocking_catalogue")
CHECK = sys.argv.pop(1)
G = 9.80665
ENV = dict(os.environ, ROCKING_CATALOGUE_CHECK=CHECK)
HEADER = ["id", "description", "sensor", "width_mm", "depth", "height", "mass", "com", "shape", "mu_s",
          "floor_material", "foot_material", "x", "y", "yaw", "scan"]


def run(*args):
    return subprocess.run([sys.executable, TOOL, *args], capture_output=True, text=True, env=ENV)


def parsed(path):
    r = subprocess.run([CHECK, path, "--json"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def inventory(n=100, seed=43):
    """Rows as the spreadsheet holds them, and what each should become in the catalogue."""
    rng = random.Random(seed)
    rows, want = [], []
    for k in range(n):
        shape = rng.choice(["box", "cylinder"])
        w = round(rng.uniform(150, 1200), 1)  # mm
        d = round(rng.uniform(0.15, 1.2), 4) if shape == "box" else None
        h = round(rng.uniform(0.3, 2.2), 4)
        uniform = rng.random() < 0.5
        if uniform:
            com, cg, nu, nuy = "uniform", h / 2, 0.5, 0.5
        else:
            cx, cy, cz = rng.uniform(-0.2, 0.2) * w / 1000, rng.uniform(-0.2, 0.2) * (d or w / 1000), rng.uniform(0.3, 0.6) * h
            com, cg, nu, nuy = f"{cx:.6f} {cy:.6f} {cz:.6f}", float(f"{cz:.6f}"), 0.5 + float(f"{cx:.6f}") / (w / 1000), \
                0.5 + float(f"{cy:.6f}") / (d or w / 1000)
        by_material = rng.random() < 0.3
        mu = 0.35 if by_material else round(rng.uniform(0.2, 0.8), 3)
        posed = rng.random() < 0.9
        x, y, yaw = round(rng.uniform(-20, 20), 3), round(rng.uniform(-10, 10), 3), round(rng.uniform(-180, 180), 2)
        desc = rng.choice(["Steel cabinet, ward 2", 'Vase "Ming"', "Cart — locked castors", "Rack; IT room", ""])
        rows.append({"id": f"item_{k:03d}", "description": desc, "sensor": f"floor_{k % 3}",
                     "width_mm": w, "depth": d if d else "", "height": h, "mass": round(rng.uniform(5, 500), 1),
                     "com": com, "shape": shape, "mu_s": "" if by_material else mu,
                     "floor_material": "vinyl" if by_material else "", "foot_material": "steel" if by_material else "",
                     "x": x if posed else "", "y": y if posed else "", "yaw": yaw if posed else "", "scan": ""})
        want.append({"id": f"item_{k:03d}", "description": desc, "sensor": f"floor_{k % 3}", "width": w / 1000,
                     "depth": d if d else w / 1000, "cg_height": cg, "eccentricity": nu, "eccentricity_y": nuy,
                     "mu_s": mu, "pose": (x, y, math.radians(yaw)) if posed else None})
    return rows, want


def write_csv(path, rows, header=HEADER):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=header)
        w.writeheader()
        w.writerows(rows)


class RoundTrip(unittest.TestCase):
    def test_hundred_rows(self):
        rows, want = inventory()
        with tempfile.TemporaryDirectory() as tmp:
            table, out = os.path.join(tmp, "items.csv"), os.path.join(tmp, "catalogue.yaml")
            write_csv(table, rows)
            r = run("from-table", table, "--out", out, "--topic", "floor_0=/lobby/imu")
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("100 items, checked by the node's parser", r.stderr)
            unposed = sum(1 for w in want if w["pose"] is None)
            self.assertIn(f"items.csv: {unposed} rows without x, y (rows ", r.stderr)
            doc = parsed(out)
            self.assertEqual(doc["sensors"], 3)
            with open(out) as fh:
                self.assertIn("topic: /lobby/imu", fh.read())
            self.assertEqual(len(doc["items"]), 100)
            for got, w in zip(doc["items"], want):
                what = w["id"]
                self.assertEqual(got["id"], w["id"])
                self.assertEqual(got["description"], w["description"], what)
                self.assertEqual(got["sensor"], w["sensor"], what)
                x = got["planes"][0]
                for k, v in (("width", w["width"]), ("cg_height", w["cg_height"]), ("mu_s", w["mu_s"])):
                    self.assertAlmostEqual(x[k], v, delta=1e-8 * abs(v), msg=f"{what} {k}")
                self.assertAlmostEqual(got["eccentricity"], w["eccentricity"], delta=1e-8, msg=what)
                self.assertAlmostEqual(got["depth"], w["depth"], delta=1e-8 * w["depth"], msg=what)
                self.assertAlmostEqual(got["eccentricity_y"], w["eccentricity_y"], delta=1e-8, msg=what)
                if w["pose"] is None:
                    self.assertNotIn("pose", got, what)
                else:
                    p = got["pose"]
                    self.assertEqual(p["parent_frame"], "accelerometer")
                    for k, v in zip(("x", "y", "yaw"), w["pose"]):
                        self.assertAlmostEqual(p[k], v, delta=1e-8, msg=f"{what} {k}")

    def test_errors_name_row_and_column(self):
        rows, _ = inventory(40)
        cases = [(("width_mm", 36, "-300"), "row 38, column 'width_mm': items[36] 'item_036': width"),
                 (("mu_s", 5, "-0.2"), "row 7, column 'mu_s': items[5] 'item_005': mu_s"),
                 (("id", 20, "item_003"), "row 22, column 'id': items[20] 'item_003': id: duplicate id"),
                 (("height", 9, "tall"), "row 11, column 'height': 'tall' is not a number"),
                 (("foot_material", 4, "glass"), "row 6, columns 'foot_material', 'floor_material': no friction")]
        with tempfile.TemporaryDirectory() as tmp:
            table, out = os.path.join(tmp, "items.csv"), os.path.join(tmp, "catalogue.yaml")
            for (col, k, value), message in cases:
                bad = [dict(r) for r in rows]
                bad[k][col] = value
                if col == "foot_material":
                    bad[k].update(mu_s="", floor_material="vinyl")
                write_csv(table, bad)
                r = run("from-table", table, "--out", out)
                self.assertEqual(r.returncode, 1, r.stderr)
                self.assertIn(message, r.stderr)
                self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
                self.assertFalse(os.path.exists(out), "nothing written on an error")
            write_csv(table, rows[:2], HEADER + ["colour"])
            r = run("from-table", table, "--out", out)
            self.assertIn("row 1, column 17 'colour': unknown column", r.stderr)


class Check(unittest.TestCase):
    def test_box_closed_forms_plan_and_scan_row(self):
        sys.path.insert(0, HERE)
        import test_mesh_input as tm
        B, D, H, mu = 0.5, 0.4, 1.6, 0.2
        rows = [{"id": "box", "sensor": "s", "width_mm": B * 1000, "depth": D, "height": H, "com": "uniform",
                 "shape": "box", "mu_s": mu, "x": 1, "y": 2, "yaw": 90},
                {"id": "loose", "sensor": "s", "width_mm": 300, "depth": 0.3, "height": 0.6, "mu_s": 0.9},
                {"id": "scanned", "sensor": "s", "mass": 80, "mu_s": 0.6, "x": 3, "y": 0, "scan": "cab.ply"}]
        with tempfile.TemporaryDirectory() as tmp:
            v, f, bottom, *_ = tm.case_box()
            tm.write(os.path.join(tmp, "cab.ply"), v * 1000, np.delete(f, bottom, axis=0), "ply")
            table, out = os.path.join(tmp, "items.csv"), os.path.join(tmp, "catalogue.yaml")
            write_csv(table, rows)
            r = run("from-table", table, "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            items = {it["id"]: it for it in parsed(out)["items"]}
            self.assertTrue(items["scanned"]["solid"])
            self.assertAlmostEqual(items["scanned"]["planes"][0]["cg_height"], 0.9, delta=1e-9)
            plan, derived = os.path.join(tmp, "plan.png"), os.path.join(tmp, "derived.csv")
            r = run("check", out, "--plan", plan, "--csv", derived)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(derived) as fh:
                table_rows = {(d["id"], d["plane"]): d for d in csv.DictReader(fh)}
            for plane, b in (("x", B), ("y", D)):
                d = table_rows[("box", plane)]
                alpha, R = math.atan(b / H), math.hypot(b, H) / 2
                self.assertAlmostEqual(float(d["alpha1_deg"]), math.degrees(alpha), places=9)
                self.assertAlmostEqual(float(d["uplift"]), G * b / H, places=9)
                self.assertAlmostEqual(float(d["p"]), math.sqrt(3 * G / (4 * R)), places=9)
                self.assertAlmostEqual(float(d["eta"]), 1 - 1.5 * math.sin(alpha) ** 2, places=9)
                psv = math.sqrt(8 / 3 * G * R * (1 - math.cos(alpha))) / math.cos(alpha)
                self.assertAlmostEqual(float(d["housner_sv"]), psv, places=9)
                self.assertAlmostEqual(float(d["ishiyama_v"]), 0.4 * psv, places=9)
                self.assertAlmostEqual(float(d["ishiyama_a"]), G * b / H, places=9)
                self.assertEqual(d["slides_first"], str(mu < b / H))  # 0.2 < 0.3125: x slides, y (0.25) too
            self.assertEqual(table_rows[("loose", "x")]["slides_first"], "False")  # 0.9 > 0.5
            # the scanned 0.9 x 0.4 x 1.8 m cabinet: 0.4 / 1.8 = 0.22 g
            self.assertIn("most easily lifted first: scanned (y, 0.22 g), box (y, 0.25 g), loose (x, 0.50 g)",
                          r.stdout)
            self.assertIn("slide before they rock (1): box", r.stdout)
            import matplotlib.image
            img = matplotlib.image.imread(plan)
            self.assertEqual(img.shape[:2], (770, 990))
            # The plan's layout is the dashboard's: posed items at their pose, the unposed one below.
            sys.path.insert(0, os.path.dirname(TOOL))
            import importlib.machinery
            import importlib.util
            loader = importlib.machinery.SourceFileLoader("rocking_catalogue", TOOL)
            rc = importlib.util.module_from_spec(importlib.util.spec_from_loader("rocking_catalogue", loader))
            loader.exec_module(rc)
            place = rc.plan_layout(list(items.values()))
            np.testing.assert_allclose(place["box"], (1, 2, math.radians(90)), rtol=1e-8)  # 9 digits written
            self.assertLess(place["loose"][1], 0.0)


class Fixture(unittest.TestCase):
    def test_rostest_catalogue_is_what_the_tool_writes(self):
        # test/ros/own_objects.test starts the monitor on this file: it must be today's output
        root = os.path.join(HERE, "..", "..")
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "c.yaml")
            r = run("from-table", os.path.join(root, "docs", "own_objects", "items.csv"), "--out", out,
                    "--topic", "ground_floor=/ground/imu")
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out) as a, open(os.path.join(root, "test", "ros", "own_objects_catalogue.yaml")) as b:
                strip = lambda t: [ln for ln in t.read().splitlines() if not ln.startswith("# made by:")]  # noqa: E731
                self.assertEqual(strip(a), strip(b))


class FromScan(unittest.TestCase):
    def test_scan_to_checked_catalogue_and_picture(self):
        sys.path.insert(0, HERE)
        import test_mesh_input as tm
        with tempfile.TemporaryDirectory() as tmp:
            v, f, bottom, *_ = tm.case_cylinder()
            scan = tm.write(os.path.join(tmp, "vase.glb"), v * 1000, np.delete(f, bottom, axis=0), "glb", y_up=True)
            out, fig = os.path.join(tmp, "c.yaml"), os.path.join(tmp, "vase.png")
            r = run("from-scan", scan, "--id", "vase", "--mass", "30", "--mu-s", "0.4", "--out", out,
                    "--figure", fig)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("unit mm (largest extent 700", r.stderr)
            self.assertIn("open: 1 hole(s), 24 boundary edges, each capped", r.stderr)
            item = parsed(out)["items"][0]
            self.assertTrue(item["solid"])
            self.assertEqual(item["pose"], {"parent_frame": "accelerometer", "x": 0, "y": 0, "yaw": 0})
            self.assertAlmostEqual(item["planes"][0]["cg_height"], 0.35, delta=1e-6)
            import matplotlib.image
            self.assertEqual(matplotlib.image.imread(fig).shape[:2], (540, 1500))
            top = np.array([k for k in range(len(f)) if v[f[k], 2].min() > 0.69])
            bad = tm.write(os.path.join(tmp, "lidless.ply"), v, np.delete(f, top, axis=0), "ply")
            r = run("from-scan", bad, "--id", "x", "--mass", "1", "--out", out + "2")
            self.assertEqual(r.returncode, 1)
            self.assertIn("open elsewhere than at its base", r.stderr)
            self.assertFalse(os.path.exists(out + "2"))

    def test_a_scan_on_a_pedestal(self):
        """--pedestal W D (issue 51): the support key, a W x D rectangle under the centre of mass, as the
        node's parser reads it; one reaching beyond the scan's base is refused by that parser, naming
        the item and the field, and nothing is written."""
        sys.path.insert(0, HERE)
        import test_mesh_input as tm
        with tempfile.TemporaryDirectory() as tmp:
            v, f, *_ = tm.case_cylinder()  # a 24-gon 0.2 m in radius (0.198 m to its sides), 0.7 m tall
            scan = tm.write(os.path.join(tmp, "vase.ply"), v, f, "ply")
            out = os.path.join(tmp, "c.yaml")
            r = run("from-scan", scan, "--id", "vase", "--mass", "30", "--unit", "m", "--pedestal", "0.2", "0.24",
                    "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            item = parsed(out)["items"][0]
            c = np.mean(np.array(item["support"]), axis=0)
            self.assertEqual(len(item["support"]), 4)
            self.assertAlmostEqual(np.ptp(np.array(item["support"])[:, 0]), 0.2, delta=1e-9)
            self.assertAlmostEqual(np.ptp(np.array(item["support"])[:, 1]), 0.24, delta=1e-9)
            self.assertAlmostEqual(item["support_margin"], 0.1, delta=1e-9)  # the nearer sides, 0.1 m away
            self.assertAlmostEqual(float(np.hypot(*c)), 0.0, delta=1e-6)  # under the axis
            self.assertAlmostEqual(item["contact_margin"], 0.1, delta=1e-9)  # the pedestal is the contact
            r = run("check", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            # lifted from rest at tan(alpha) = 0.1 / 0.35 on the pedestal (0.198 / 0.35 on the floor)
            self.assertIn("on a support (1; the 3-D model on its top decides): vase (lifted from rest at 0.29 g on "
                          "it; centre of mass 0.100 m inside its edge)", r.stdout)
            for bad, says in ((("0.3", "0.3"), "support: with a hull, the support must lie within base_polygon"),
                              (("0", "0.2"), "--pedestal: width and depth must be finite values > 0 m")):
                r = run("from-scan", scan, "--id", "vase", "--mass", "30", "--unit", "m", "--pedestal", *bad,
                        "--out", out + "2")
                self.assertEqual(r.returncode, 1, r.stderr)
                self.assertIn(says, r.stderr)
                self.assertFalse(os.path.exists(out + "2"))
            r = run("from-scan", scan, "--id", "vase", "--mass", "30", "--unit", "m", "--out", out)
            self.assertIsNone(parsed(out)["items"][0]["support"])

    def test_progress_only_on_a_terminal(self):
        """from-scan's stage bar (issue 53): off a terminal stderr is the --quiet run's, byte for byte;
        on a pseudo-terminal it reaches all of scan_geometry's stages; --quiet draws nothing there."""
        sys.path.insert(0, HERE)
        import test_mesh_input as tm
        from test_progress_bar import read_all
        with tempfile.TemporaryDirectory() as tmp:
            v, f, *_ = tm.case_cylinder()
            scan = tm.write(os.path.join(tmp, "jar.ply"), v, f, "ply")
            args = ["from-scan", scan, "--id", "jar", "--mass", "3", "--out", os.path.join(tmp, "c.yaml")]
            piped, quiet = run(*args), run(*args, "--quiet")
            self.assertEqual((piped.returncode, quiet.returncode), (0, 0), piped.stderr)
            self.assertEqual(piped.stderr, quiet.stderr)
            self.assertNotIn("\r", piped.stderr)
            for extra, drawn in (([], True), (["--quiet"], False)):
                master, slave = os.openpty()
                try:
                    r = subprocess.run([sys.executable, TOOL, *args, *extra], stderr=slave,
                                       stdout=subprocess.DEVNULL, env=ENV)
                    os.close(slave)
                    text = read_all(master)
                finally:
                    os.close(master)
                self.assertEqual(r.returncode, 0, text)
                self.assertEqual("from-scan jar.ply" in text and "7/7" in text, drawn, text)


if __name__ == "__main__":
    unittest.main(verbosity=2)
