#!/usr/bin/python3
"""calibrate_experiments: the fit recovers a known grid point and noise level from synthetic data,
cross-validation never sees a held-out outcome, the helpers (folds, scores, resampling) give their
exact values, and the whole pipeline (rocking_geometry.py on box meshes, a stub rocking_experiments,
cache, calibrated catalogue) recovers the setting that made the outcomes."""
import contextlib
import gzip
import io
import json
import os
import math
import re
import sys
import tempfile
import unittest

import numpy as np
import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
import calibrate_experiments as ce  # noqa: E402


def synthetic(seed=5, n=300, e_star=0.1, k_star=7):
    """A fake prediction matrix: random rows, and rows that differ from the true row k* in 10, 20 or
    40 tests (near neighbours the fit must tell apart); outcomes = row k* with each test flipped with
    probability e*."""
    rng = np.random.default_rng(seed)
    pred = (rng.random((16, n)) < 0.4).astype(float)
    for k, d in ((3, 10), (9, 20), (12, 40)):
        pred[k] = pred[k_star]
        idx = rng.choice(n, d, replace=False)
        pred[k, idx] = 1 - pred[k, idx]
    y = pred[k_star].astype(int)
    flip = rng.random(n) < e_star
    y[flip] = 1 - y[flip]
    return pred, y, int(flip.sum()) / n


class Synthetic(unittest.TestCase):
    def test_recovers_k_star_and_e(self):
        pred, y, e_real = synthetic()
        self.assertGreater(e_real, 0.05)  # the data are noisy, not trivially separable
        for method in ("integrate", "max"):
            f = ce.fit(pred, y, method=method)
            self.assertEqual(f["map"], 7, method)
            self.assertLess(abs(f["e_mean"] - 0.1), 0.05, method)
            self.assertLess(abs(f["e_map"] - 0.1), 0.05, method)
            self.assertAlmostEqual(f["weights"].sum(), 1.0, places=12)

    def test_cross_validated_accuracy_is_one_minus_e(self):
        pred, y, e_real = synthetic()
        r = ce.evaluate(pred, y, folds_k=10, seed=20)
        self.assertEqual(r["cv"]["tests"], 300)
        self.assertLess(abs(r["cv"]["accuracy"] - 0.9), 0.05)
        # every fold finds k*, so the held-out labels are row k*'s: wrong exactly on the flips
        self.assertTrue(all(f["map"] == 7 for f in r["cv_folds"]))
        self.assertAlmostEqual(r["cv"]["accuracy"], 1 - e_real, places=12)
        self.assertAlmostEqual(r["loo"]["accuracy"], 1 - e_real, places=12)
        self.assertAlmostEqual(r["in_sample"]["accuracy"], 1 - e_real, places=12)
        self.assertLess(r["cv"]["brier_with_e"], r["cv"]["brier"])  # 0/1 P is over-confident

    def test_a_held_out_outcome_never_enters_its_fold(self):
        pred, y, _ = synthetic(seed=8, n=120)
        pred[3] = pred[7]
        pred[3, :30] = 1 - pred[3, :30]  # a near rival: the weights respond to single outcomes
        folds = ce.stratified_folds(y, 10, 1)
        p, fits = ce.cross_validate(pred, y, folds)
        i = int(np.flatnonzero(folds == 4)[0])  # a test of fold 4
        y2 = y.copy()
        y2[i] = 1 - y2[i]
        p2, fits2 = ce.cross_validate(pred, y2, folds)
        self.assertEqual(p[i], p2[i])
        np.testing.assert_array_equal(fits[4]["weights"], fits2[4]["weights"])
        # ... while every other fold, which trains on test i, does change
        for f in range(10):
            if f != 4:
                self.assertFalse(np.array_equal(fits[f]["weights"], fits2[f]["weights"]), f)

    def test_identical_points_share_weight_and_anti_predictions_get_none(self):
        pred, y, _ = synthetic()
        both = np.vstack([pred, pred[7], 1 - pred[7]])  # a duplicate of k* and its negation
        w = ce.fit(both, y)["weights"]
        self.assertAlmostEqual(w[7], w[16], places=12)
        self.assertAlmostEqual(w[7] + w[16], 1.0, places=6)
        self.assertLess(w[17], 1e-12)  # e < 0.5: mostly wrong is not rewarded

    def test_bad_shapes_are_refused(self):
        with self.assertRaisesRegex(ce.CalibrationError, "do not match"):
            ce.fit(np.zeros((2, 5)), np.zeros(4, dtype=int))
        with self.assertRaisesRegex(ce.CalibrationError, "0 or 1"):
            ce.fit(np.zeros((2, 3)), np.array([0, 2, 1]))


class Helpers(unittest.TestCase):
    def test_stratified_folds(self):
        y = np.array([1] * 37 + [0] * 63)
        f = ce.stratified_folds(y, 10, 3)
        np.testing.assert_array_equal(f, ce.stratified_folds(y, 10, 3))  # fixed seed
        self.assertEqual(sorted(np.bincount(f).tolist()), [10] * 10)
        for k in range(10):
            self.assertIn(int(y[f == k].sum()), (3, 4))  # 37 overturns over 10 folds
        with self.assertRaisesRegex(ce.CalibrationError, "--folds 1"):
            ce.stratified_folds(y, 1, 3)

    def test_scores(self):
        p = np.array([0.9, 0.6, 0.2, 0.5, 0.1, 0.4])
        y = np.array([1, 0, 0, 1, 1, 0])
        s = ce.scores(p, y)
        self.assertEqual((s["tp"], s["fp"], s["tn"], s["fn"]), (2, 1, 2, 1))
        self.assertAlmostEqual(s["accuracy"], 4 / 6)
        self.assertAlmostEqual(s["precision"], 2 / 3)
        self.assertAlmostEqual(s["recall"], 2 / 3)
        self.assertAlmostEqual(s["f1"], 2 / 3)
        self.assertAlmostEqual(s["brier"], (0.01 + 0.36 + 0.04 + 0.25 + 0.81 + 0.16) / 6)
        self.assertIsNone(ce.scores(np.zeros(3), np.zeros(3, dtype=int))["precision"])

    def test_systematic_resampling_and_support(self):
        np.testing.assert_array_equal(ce.systematic_resample([0.5, 0.3, 0.2], 20), [10, 6, 4])
        c = ce.systematic_resample([0.37, 0.33, 0.2, 0.1], 7)
        self.assertEqual(int(c.sum()), 7)
        for n, w in zip(c, (0.37, 0.33, 0.2, 0.1)):
            self.assertIn(int(n), (int(np.floor(7 * w)), int(np.ceil(7 * w))))
        w = np.array([1e-5, 0.5, 0.2, 0.2999])
        self.assertEqual(ce.support(w), [1, 3, 2])
        self.assertEqual(ce.support(np.ones(30)), list(range(20)))

    def test_grid_errors_name_the_field(self):
        for doc, msg in (
                ({"specimens": {"SP1": {"contact_tolerance_mm": "1"}}}, "specimens: SP1: contact_tolerance_mm"),
                ({"specimens": {"SP1": {"com": ["measured"]}}}, "specimens: SP1: com"),
                ({"specimens": {"SP1": {"tolerance": [1]}}}, "specimens: SP1: unknown field.*tolerance"),
                ({"specimens": {"SP1": {}}, "runtime": [["--restitution", 0.8], ["--restitution", "0.8"]]},
                 "runtime: an argument list appears twice"),
                ({"specimens": {}}, "specimens: a non-empty map"),
                ({"specimens": {"SP1": {}}, "runtim": []}, "unknown field.*runtim")):
            with self.assertRaisesRegex(ce.CalibrationError, "^g.json: " + msg):
                ce.parse_grid(doc, "g.json")
        g = ce.parse_grid({"specimens": {"SP2": {"contact_tolerance_mm": [1, 2], "com": ["stated", "homogeneous"]}},
                           "runtime": [[], ["--model", "3d"]]}, "g")
        self.assertEqual(len(g["points"]["SP2"]), 8)

    def test_runtime_keys(self):
        self.assertEqual(ce.runtime_keys(["--model", "3d", "--restitution", "0.8"], "p"),
                         ([("restitution", "0.8")], ["--model", "3d"]))

    def test_table_azimuth_becomes_the_items_yaw(self):
        # the table's axis at -5 deg in the specimen's frame: the specimen turned by +5 deg on it
        keys, rest = ce.runtime_keys(["--table-azimuth", "-5"], "p")
        self.assertEqual(rest, [])
        self.assertEqual(keys[0][0], "pose")
        yaw = float(keys[0][1].split("yaw:")[1].split("}")[0])
        self.assertAlmostEqual(yaw, math.radians(5.0), places=12)


# ---------------------------------------------------------------- the pipeline, end to end

STUB = r'''#!/usr/bin/python3
# A stand-in for rocking_experiments: a deterministic pseudo-random prediction per test from the
# item's eccentricities and the restitution (so every distinct grid point has its own row).
import csv, math, re, sys
a = sys.argv[1:]
data, opts = a[0], {a[i]: a[i + 1] for i in range(1, len(a) - 1, 2)}
items, cur = [], None
for line in open(opts["--catalogue"]):
    m = re.match(r"\s*- id: (\S+)", line)
    if m:
        cur = {"id": m.group(1)}
        items.append(cur)
    m = re.match(r"\s+(eccentricity|eccentricity_y|restitution): ([-0-9.e]+)", line)
    if m and cur is not None:
        cur[m.group(1)] = float(m.group(2))
r = float(opts.get("--restitution", "0.5"))
rows = list(csv.DictReader(open(data + "/outcomes.csv")))
with open(opts["--out"], "w") as out:
    out.write("test,specimen,peak_table_accel_mps2,offset_mps2,exceeds_static_uplift,uplift,"
              "max_rotation_ratio,impacts,overturn_time_s,predicted_overturned,measured_overturned,"
              "members,p_overturn\n")
    for row in rows:
        t = int(row["test"])
        for it in items:
            name = it["id"].split("#")[0]
            s = it["eccentricity"] * 7.1 + it["eccentricity_y"] * 3.3 + it.get("restitution", r) * 5.7
            pred = int(math.modf(abs(math.sin(t * 12.9898 + 78.233 * s)) * 43758.5453)[0] < 0.4)
            out.write(f"{t},{name},0,0,0,0,0,0,0,{pred},{row[name.lower() + '_overturned']},1,{pred:.4f}\n")
'''


def write_box_obj_gz(path, lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    with gzip.open(path, "wt") as out:
        for p in v:
            out.write("v %r %r %r\n" % p)
        for q in quads:
            out.write("f %d %d %d %d\n" % tuple(i + 1 for i in q))


class Pipeline(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        d = self.tmp.name
        self.data = os.path.join(d, "granite")
        os.makedirs(os.path.join(self.data, "specimens"))
        os.makedirs(os.path.join(self.data, "tests"))
        # boxes big enough that SP2's stated centre (-0.033, 0.029) m lies over the base
        write_box_obj_gz(os.path.join(self.data, "specimens", "SP1_pca.obj.gz"), (-0.2, -0.15, -0.3), (0.2, 0.15, 0.3))
        write_box_obj_gz(os.path.join(self.data, "specimens", "SP2.obj.gz"), (-0.2, -0.25, -0.3), (0.2, 0.25, 0.3))
        self.n = 200
        for t in range(1, self.n + 1):
            open(os.path.join(self.data, "tests", f"Test{t:03d}.csv"), "w").close()
        self.write_outcomes(np.zeros(self.n, dtype=int), np.zeros(self.n, dtype=int))
        self.stub = os.path.join(d, "rocking_experiments_stub")
        with open(self.stub, "w") as fh:
            fh.write(STUB)
        os.chmod(self.stub, 0o755)
        self.grid = os.path.join(d, "grid.json")
        with open(self.grid, "w") as fh:
            json.dump({"specimens": {
                "SP1": {"contact_tolerance_mm": [1, 2], "com": ["stated", "homogeneous"]},
                "SP2": {"contact_tolerance_mm": [1, 2], "com": ["stated", "homogeneous"],
                        "com_shift_mm": [[0, 0], [500, 0]]}},
                "runtime": [[], ["--restitution", "0.8"]], "geometry_args": ["--planar-only"],
                "common_args": ["--direction", "1"]}, fh)

    def tearDown(self):
        self.tmp.cleanup()

    def write_outcomes(self, sp1, sp2):
        with open(os.path.join(self.data, "outcomes.csv"), "w") as fh:
            fh.write("test,sp1_overturned,sp2_overturned\n")
            for t in range(self.n):
                fh.write(f"{t + 1},{sp1[t]},{sp2[t]}\n")

    def run_main(self, *extra):
        d = self.tmp.name
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            rc = ce.main(["--granite", self.data, "--experiments", self.stub, "--grid", self.grid,
                          "--cache-dir", os.path.join(d, "cache"), "--out-dir", os.path.join(d, "out"),
                          "--python", "/usr/bin/python3", *extra])
        with open(os.path.join(d, "out", "summary.json")) as fh:
            return rc, err.getvalue(), json.load(fh)

    def grid_columns(self, name):
        with open(os.path.join(self.tmp.name, "out", f"predictions_{name}.csv")) as fh:
            rows = list(csvreader(fh))
        cols = [c for c in rows[0] if c.startswith("grid")]
        return np.array([[float(r[c]) for c in cols] for r in rows]).T

    def test_recovers_the_setting_that_made_the_outcomes(self):
        rc, err, s = self.run_main()
        self.assertEqual(rc, 0, err)
        # stderr is not a terminal here: no progress bar in it (issue 53, scripts/progress_bar.py)
        self.assertNotIn("\r", err)
        self.assertNotIn("calibrate_experiments: grid points", err)  # the bar's label
        # SP1 has no stated centre and a box's contact does not depend on the tolerance: 2 distinct
        # points (the runtime settings); SP2: 2 centres x 2 runtimes; the 500 mm shift is refused.
        self.assertEqual(s["specimens"]["SP1"]["grid_points"], 2)
        self.assertEqual(s["specimens"]["SP2"]["grid_points"], 4)
        self.assertEqual(len(s["refused"]), 8)  # SP2, 500 mm: 2 tolerances x 2 centres x 2 runtimes
        self.assertIn("not over the base", s["refused"][0]["reason"])
        self.assertIn("6 grid points (6 run, 0 cached)", err)
        self.assertEqual(s["specimens"]["SP1"]["points"][0]["setting"], "tol 1 mm = 2 mm, com stated = homogeneous, defaults")
        sp1, sp2 = self.grid_columns("SP1"), self.grid_columns("SP2")
        k1, k2 = 1, 2  # the truth: SP1 with --restitution 0.8, SP2's third point
        rng = np.random.default_rng(4)
        y1, y2 = sp1[k1].astype(int), sp2[k2].astype(int)
        for y in (y1, y2):
            flip = rng.random(self.n) < 0.1
            y[flip] = 1 - y[flip]
        self.write_outcomes(y1, y2)
        rc, err, s = self.run_main("--write-catalogue", os.path.join(self.tmp.name, "cal.yaml"), "--members", "10")
        self.assertEqual(rc, 0, err)
        self.assertIn("6 grid points (6 run, 0 cached)", err)  # new outcomes: the cache does not apply
        self.assertEqual(s["specimens"]["SP1"]["map"]["index"], k1)
        self.assertEqual(s["specimens"]["SP2"]["map"]["index"], k2)
        self.assertIn("--restitution 0.8", s["specimens"]["SP1"]["map"]["setting"])
        for name, y, k in (("SP1", y1, k1), ("SP2", y2, k2)):
            want = float(((s["specimens"][name]["points"][k]["accuracy"])))
            self.assertAlmostEqual(want, float((y == (sp1 if name == "SP1" else sp2)[k]).mean()))
            self.assertGreater(s["specimens"][name]["cv"]["accuracy"], 0.8)
            self.assertLess(abs(s["specimens"][name]["e_mean"] - 0.1), 0.05)
        self.assertEqual(s["both"]["cv"]["tests"], 2 * self.n)
        for kind in ("in_sample", "cv", "loo"):  # equal test counts: both = the mean of the two
            for key in ("accuracy", "brier", "brier_with_e"):
                self.assertAlmostEqual(s["both"][kind][key], (s["specimens"]["SP1"][kind][key] +
                                                              s["specimens"]["SP2"][kind][key]) / 2, places=12)
        with open(os.path.join(self.tmp.name, "cal.yaml")) as fh:
            text = fh.read()
        self.assertIn("# made by: calibrate_experiments.py", text)
        self.assertIn("systematic resampling", text)
        self.assertIn("# Run rocking_experiments with these arguments (common to every member): --direction 1\n", text)
        items = yaml.safe_load(text)["items"]
        self.assertEqual([i["id"] for i in items], [f"SP1#{j}" for j in range(10)] + [f"SP2#{j}" for j in range(10)])
        # the SP1 posterior sits on the --restitution 0.8 point: its members carry the key
        self.assertTrue(all(i.get("restitution") == 0.8 for i in items[:10]))
        self.assertTrue(all("centre_of_mass" not in i for i in items))  # --planar-only passed through
        # and unchanged inputs: everything from the cache
        rc, err, _ = self.run_main()
        self.assertIn("6 grid points (0 run, 6 cached)", err)

    def test_bad_inputs_are_one_clear_error(self):
        bad = os.path.join(self.tmp.name, "bad.json")
        with open(bad, "w") as fh:
            fh.write('{"specimens": {"SP1": {"com": ["x"]}}}')
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            rc = ce.main(["--granite", self.data, "--experiments", self.stub, "--grid", bad,
                          "--cache-dir", os.path.join(self.tmp.name, "c"), "--out-dir", os.path.join(self.tmp.name, "o")])
        self.assertEqual(rc, 2)
        self.assertRegex(err.getvalue(), r"^calibrate_experiments: error: .*bad.json: specimens: SP1: com")
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            rc = ce.main(["--granite", self.data, "--experiments", os.path.join(self.tmp.name, "nope"), "--grid",
                          self.grid, "--cache-dir", os.path.join(self.tmp.name, "c"), "--out-dir", os.path.join(self.tmp.name, "o")])
        self.assertEqual(rc, 2)
        self.assertIn("--experiments", err.getvalue())
        table = os.path.join(self.tmp.name, "t.csv")
        with open(table, "w") as fh:
            fh.write("test,specimen,predicted_overturned\n1,SP1,0\n")
        with self.assertRaisesRegex(ce.CalibrationError, re.escape(table) + ": missing column.*measured_overturned"):
            ce.read_table(table, "SP1")


class UrdfCentre(unittest.TestCase):
    """SP2's third centre of mass (issue 51): the one the Virtual Shake Robot's sp2.urdf simulates,
    (+0.033, -0.029, -0.001) m in the mesh frame, the stated one's opposite, is offered on the grid
    like the other two and chosen inside the folds like them."""

    def test_offered_on_the_grid_and_the_command_line(self):
        self.assertEqual(ce.COM_CANDIDATES, ("stated", "homogeneous", "urdf"))
        g = ce.parse_grid({"specimens": {"SP2": {"contact_tolerance_mm": [1, 2],
                                                 "com": ["stated", "homogeneous", "urdf"]}}}, "g")
        self.assertEqual(sorted({geo["com"] for geo, _ in g["points"]["SP2"]}), ["homogeneous", "stated", "urdf"])
        self.assertEqual(len(g["points"]["SP2"]), 6)
        # the grid file of docs/validation.md's run: SP2 on the azimuth grid with the three centres
        path = os.path.join(HERE, "..", "..", "config", "calibration_grid_3d_azimuth_sp2_urdf.json")
        g = ce.parse_grid(ce.load_grid_file(path), path)
        self.assertEqual(list(g["points"]), ["SP2"])
        self.assertEqual(len(g["points"]["SP2"]), 6 * 3 * 12)
        self.assertEqual(sum(geo["com"] == "urdf" for geo, _ in g["points"]["SP2"]), 6 * 12)
        a = ce.parser().parse_args(["--granite", "d", "--experiments", "x", "--cache-dir", "c", "--out-dir", "o",
                                    "--com", "stated", "homogeneous", "urdf"])
        self.assertEqual(ce.grid_from_flags(a)["specimens"]["SP2"]["com"], ["stated", "homogeneous", "urdf"])

    def test_rocking_geometry_gets_the_urdf_centre_standing_as_placed(self):
        geo = {"contact_tolerance_m": 0.002, "com": "urdf", "com_shift_m": [0.0, 0.0]}
        args = ce.geometry_args("data", "SP2", geo, [])
        self.assertIn("--urdf-com", args)
        self.assertIn("--no-settle", args)  # settling would lay SP2 on its side: the tests began upright
        self.assertNotIn("--homogeneous", args)
        for com in ("stated", "homogeneous"):  # the other two unchanged: settled, as before
            self.assertNotIn("--no-settle", ce.geometry_args("data", "SP2", dict(geo, com=com), []))
        import rocking_geometry as rg
        urdf, stated = rg.specimen_specs(urdf_com=True), rg.specimen_specs()
        self.assertEqual(urdf["SP2"]["com"], (0.033, -0.029, -0.001))
        self.assertEqual(urdf["SP2"]["com"], tuple(-c for c in stated["SP2"]["com"]))
        self.assertIsNone(urdf["SP1"]["com"])  # sp1.urdf: the principal-frame mesh's own centre
        with self.assertRaises(rg.GeometryError):
            rg.specimen_specs(homogeneous=True, urdf_com=True)

    def test_real_sp2_stands_on_the_urdf_centre_only_from_1_5_mm(self):
        granite = os.path.join(HERE, "..", "..", "..", "shared", "experiments", "granite_pbr")
        if not os.path.isfile(os.path.join(granite, "specimens", "SP2.obj.gz")):
            self.skipTest("../shared/experiments/granite_pbr not here")
        import subprocess
        tool = os.path.join(HERE, "..", "..", "scripts", "rocking_geometry.py")
        for tol, rc in ((0.001, 2), (0.0015, 0)):
            geo = {"contact_tolerance_m": tol, "com": "urdf", "com_shift_m": [0.0, 0.0]}
            r = subprocess.run(["/usr/bin/python3", tool] + ce.geometry_args(granite, "SP2", geo, []),
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, rc, r.stderr)
            if rc:
                self.assertIn("centre of mass (x, y = 0.033, -0.029 m) is not over the base", r.stderr)
            else:
                self.assertIn("centre_of_mass: [0.033, -0.029,", r.stdout)

    def test_pipeline_gives_the_urdf_centre_its_own_grid_point(self):
        with tempfile.TemporaryDirectory() as d:
            data = os.path.join(d, "granite")
            os.makedirs(os.path.join(data, "specimens"))
            os.makedirs(os.path.join(data, "tests"))
            write_box_obj_gz(os.path.join(data, "specimens", "SP1_pca.obj.gz"), (-0.2, -0.15, -0.3), (0.2, 0.15, 0.3))
            write_box_obj_gz(os.path.join(data, "specimens", "SP2.obj.gz"), (-0.2, -0.25, -0.3), (0.2, 0.25, 0.3))
            with open(os.path.join(data, "outcomes.csv"), "w") as fh:
                fh.write("test,sp1_overturned,sp2_overturned\n")
                for t in range(1, 41):
                    open(os.path.join(data, "tests", f"Test{t:03d}.csv"), "w").close()
                    fh.write(f"{t},{t % 2},{t % 3 == 0:d}\n")
            stub = os.path.join(d, "stub")
            with open(stub, "w") as fh:
                fh.write(STUB)
            os.chmod(stub, 0o755)
            grid = os.path.join(d, "grid.json")
            with open(grid, "w") as fh:
                json.dump({"specimens": {"SP2": {"contact_tolerance_mm": [1], "com": ["stated", "homogeneous", "urdf"]}},
                           "geometry_args": ["--planar-only"]}, fh)
            err = io.StringIO()
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                rc = ce.main(["--granite", data, "--experiments", stub, "--grid", grid, "--folds", "4",
                              "--cache-dir", os.path.join(d, "cache"), "--out-dir", os.path.join(d, "out"),
                              "--python", "/usr/bin/python3"])
            self.assertEqual(rc, 0, err.getvalue())
            with open(os.path.join(d, "out", "summary.json")) as fh:
                s = json.load(fh)["specimens"]["SP2"]
            # three centres, three models (the box carries all three): the URDF's is a point of its own
            self.assertEqual(s["grid_points"], 3)
            self.assertEqual([p["geometry"]["com"] for p in s["points"]], ["stated", "homogeneous", "urdf"])
            self.assertEqual(s["points"][2]["setting"], "tol 1 mm, com urdf, defaults")
            self.assertEqual(len(s["cv_map_per_fold"]), 4)  # chosen inside each fold like the others
            self.assertTrue(all(0 <= k < 3 for k in s["cv_map_per_fold"]))


def csvreader(fh):
    import csv
    return csv.DictReader(fh)


if __name__ == "__main__":
    unittest.main()
