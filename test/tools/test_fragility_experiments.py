#!/usr/bin/python3
"""fragility_experiments.py (issue 41): the overturn intervals from a margin search, P against the
lognormal's closed form, maximum likelihood recovering a known (mu, beta) from synthetic outcomes,
cross-validation that never sees a held-out outcome, the Poisson-binomial band against the binomial,
and the pipeline end to end with a stand-in rocking_experiments (cache, catalogue, errors)."""
import math
import os
import subprocess
import sys
import tempfile
import textwrap
import unittest

import numpy as np
from scipy import stats

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.join(HERE, "..", "..", "scripts")
sys.path.insert(0, SCRIPTS)
import fragility_experiments as F  # noqa: E402

GRID = F.grid_scales(0.25, 4.0, 9)


def write(path, text):
    with open(path, "w") as fh:
        fh.write(text)


def read(path):
    with open(path) as fh:
        return fh.read()


def monotone_segments(ln_s):
    return F.Segments([[[(v, math.inf)] for v in ln_s]], len(ln_s))


class Segments(unittest.TestCase):
    def test_monotone_pattern_is_one_interval_from_the_bracket_midpoint(self):
        segs = F.overturn_segments("000001111", GRID, 1.30, 1.32)
        self.assertEqual(len(segs), 1)
        self.assertAlmostEqual(segs[0][0], 0.5 * (math.log(1.30) + math.log(1.32)), places=14)
        self.assertEqual(segs[0][1], math.inf)

    def test_chaotic_pattern_gives_two_intervals(self):
        segs = F.overturn_segments("000110111", GRID, 0.6, 0.62)
        self.assertEqual(len(segs), 2)
        self.assertAlmostEqual(segs[0][1], 0.5 * (math.log(GRID[4]) + math.log(GRID[5])), places=14)
        self.assertAlmostEqual(segs[1][0], 0.5 * (math.log(GRID[5]) + math.log(GRID[6])), places=14)

    def test_censored_patterns(self):
        self.assertEqual(F.overturn_segments("111111111", GRID, 0.25, 0.25), [(-math.inf, math.inf)])
        self.assertEqual(F.overturn_segments("000000000", GRID, 4.0, 4.0), [])

    def test_p_is_the_lognormal_closed_form_for_monotone_tests(self):
        ln_s = np.array([-1.0, -0.2, 0.0, 0.3, 1.1])
        p = F.fragility_p(monotone_segments(ln_s), [1.0], -0.15, 0.4)
        np.testing.assert_allclose(p, stats.norm.cdf(-(ln_s - 0.15) / 0.4), rtol=0, atol=1e-15)

    def test_members_are_weighted(self):
        seg = F.Segments([[[(0.0, math.inf)]], [[(-math.inf, math.inf)]]], 1)
        self.assertAlmostEqual(F.fragility_p(seg, [0.25, 0.75], 0.0, 0.3)[0], 0.25 * 0.5 + 0.75, places=14)


class Fit(unittest.TestCase):
    def synthetic(self, n, mu, beta, seed):
        rng = np.random.default_rng(seed)
        ln_s = rng.uniform(-1.5, 1.5, n)
        y = (rng.uniform(size=n) < stats.norm.cdf(-(ln_s + mu) / beta)).astype(int)
        return ln_s, y

    def test_maximum_likelihood_recovers_a_known_fragility(self):
        ln_s, y = self.synthetic(4000, -0.2, 0.35, 41)
        r = F.fit_fragility(monotone_segments(ln_s), [1.0], y)
        # standard errors at n = 4000 are ~0.01 (mu) and ~0.01 (beta)
        self.assertAlmostEqual(r["mu"], -0.2, delta=0.04)
        self.assertAlmostEqual(r["beta"], 0.35, delta=0.04)
        r0 = F.fit_fragility(monotone_segments(ln_s), [1.0], y, fix_mu=0.0)
        self.assertEqual(r0["mu"], 0.0)
        self.assertGreater(r0["nll"], r["nll"])

    def test_cross_validation_never_sees_a_held_out_outcome(self):
        ln_s, y = self.synthetic(300, 0.1, 0.3, 7)
        seg = monotone_segments(ln_s)
        folds = F.stratified_folds(y, 10, 20)
        p, _ = F.cross_validate(seg, [1.0], y, folds)
        i = int(np.flatnonzero(folds == 3)[0])
        y2 = y.copy()
        y2[i] = 1 - y2[i]
        p2, _ = F.cross_validate(seg, [1.0], y2, folds)
        held = folds == 3
        np.testing.assert_array_equal(p[held], p2[held])  # bit-identical
        self.assertFalse(np.array_equal(p[~held], p2[~held]))  # it is used by the other folds

    def test_band_is_the_binomial_when_the_ps_are_equal(self):
        lo, hi = F.poisson_binomial_band([0.3] * 40)
        self.assertEqual((lo, hi), (int(stats.binom.ppf(0.025, 40, 0.3)), int(stats.binom.ppf(0.975, 40, 0.3))))

    def test_reliability_of_outcomes_drawn_from_their_p_is_inside_the_band(self):
        rng = np.random.default_rng(3)
        p = rng.uniform(size=2000)
        y = (rng.uniform(size=2000) < p).astype(int)
        rows = F.reliability(p, y)
        self.assertEqual(len(rows), 10)
        self.assertGreaterEqual(sum(r["inside"] for r in rows), 9)  # 95 % bands: about 1 in 20 out
        # outcomes that ignore P fail it
        bad = F.reliability(p, np.zeros(2000, dtype=int))
        self.assertLessEqual(sum(r["inside"] for r in bad), 1)


STUB = textwrap.dedent('''\
    #!/usr/bin/python3
    # Stand-in for rocking_experiments --margins: margin s* = 2^(x) with x from the catalogue's
    # 'width' (a stand-in geometry) and the test number; counts its runs in a file.
    import math, os, sys
    a = sys.argv
    cat = open(a[a.index("--catalogue") + 1]).read()
    width = float([l for l in cat.splitlines() if "width:" in l][0].split(":")[1])
    name = [l for l in cat.splitlines() if "- id:" in l][0].split(":")[1].strip()
    out = a[a.index("--margins") + 1]
    outcomes = dict(l.split(",", 1) for l in open(os.path.join(a[1], "outcomes.csv")).read().split()[1:])
    col = 0 if name == "SP1" else 1
    with open(os.environ["STUB_COUNT"], "a") as fh:
        fh.write("run\\n")
    n = int(a[a.index("--margin-grid") + 1])
    grid = [0.25 * 16 ** (k / (n - 1)) for k in range(n)]
    with open(out, "w") as fh:
        fh.write("test,specimen,member,measured_overturned,peak_table_accel_mps2,margin_scale,censored,chaotic,"
                 "grid_outcomes,bracket_lo,bracket_hi,runs\\n")
        for t in sorted(outcomes, key=int):
            s = 2 ** (math.sin(int(t) * width) * 1.5)
            pat = "".join("1" if g >= s else "0" for g in grid)
            k = pat.find("1")
            lo, hi = (grid[k - 1], grid[k]) if k > 0 else ((0.25, 0.25) if k == 0 else (4, 4))
            cen = 0 if k > 0 else (-1 if k == 0 else 1)
            fh.write(f"{t},{name},0,{outcomes[t].split(',')[col]},1.0,{s},{cen},0,{pat},{lo},{hi},{n}\\n")
    print("stub")
''')


class Pipeline(unittest.TestCase):
    def test_end_to_end_with_a_stand_in(self):
        with tempfile.TemporaryDirectory() as d:
            os.makedirs(os.path.join(d, "data", "tests"))
            rng = np.random.default_rng(5)
            lines = ["test,sp1_overturned,sp2_overturned"]
            for t in range(1, 121):
                s1, s2 = 2 ** (math.sin(t * 0.2) * 1.5), 2 ** (math.sin(t * 0.3) * 1.5)
                y1 = int(rng.uniform() < stats.norm.cdf(-(math.log(s1) - 0.1) / 0.3))
                y2 = int(rng.uniform() < stats.norm.cdf(-(math.log(s2) - 0.1) / 0.3))
                lines.append(f"{t},{y1},{y2}")
                write(os.path.join(d, "data", "tests", f"Test{t:03d}.csv"), "time_s,table_accel_g\n")
            write(os.path.join(d, "data", "outcomes.csv"), "\n".join(lines) + "\n")
            stub = os.path.join(d, "stub")
            write(stub, STUB)
            os.chmod(stub, 0o755)
            cat = os.path.join(d, "cat.yaml")
            write(cat, "items:\n" + "".join(
                f"  - id: {n}#{k}\n    # a comment\n    width: {w}\n    cg_height: 0.5\n"
                for n, w, k in (("SP1", 0.2, 0), ("SP1", 0.2, 1), ("SP1", 0.2, 2), ("SP2", 0.3, 0), ("SP2", 0.31, 1))))
            env = dict(os.environ, STUB_COUNT=os.path.join(d, "count"))
            cmd = [sys.executable, os.path.join(SCRIPTS, "fragility_experiments.py"), "--granite", os.path.join(d, "data"),
                   "--experiments", stub, "--catalogue", cat, "--cache-dir", os.path.join(d, "cache"),
                   "--out-dir", os.path.join(d, "out"), "--write-catalogue", os.path.join(d, "frag.yaml"), "--members", "40"]
            r = subprocess.run(cmd, capture_output=True, text=True, env=env)
            self.assertEqual(r.returncode, 0, r.stderr)
            # stderr is a pipe, not a terminal: no progress bar in it (issue 53, scripts/progress_bar.py)
            self.assertNotIn("\r", r.stderr)
            self.assertNotIn("fragility_experiments: members", r.stderr)
            self.assertEqual(len(read(os.path.join(d, "count")).split()), 3)  # SP1 once, SP2 twice
            self.assertIn("members [3]", r.stdout)
            self.assertIn("members [1, 1]", r.stdout)
            text = read(os.path.join(d, "frag.yaml"))
            self.assertEqual(text.count("input_gain: {lognormal: ["), 2)
            self.assertEqual(text.count("ensemble_size: 40"), 2)
            self.assertIn("  - id: SP1\n", text)
            self.assertIn("    width: 0.2\n", text)
            # the fit on the data drawn with mu = -0.1 (the stub's ln s* + mu... sign: P = Phi(-(ln s - 0.1)/0.3))
            mu = float(text.split("mu ")[1].split(",")[0])
            self.assertAlmostEqual(mu, -0.1, delta=0.15)
            # rerun: everything cached; and the written catalogue is itself an input (its input_gain set aside)
            r = subprocess.run(cmd[:cmd.index("--catalogue") + 1] + [os.path.join(d, "frag.yaml")] +
                               cmd[cmd.index("--catalogue") + 2:-4], capture_output=True, text=True, env=env)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(len(read(os.path.join(d, "count")).split()), 3)
            self.assertIn("(2 cached)", r.stdout)
            bad = subprocess.run(cmd[:cmd.index("--catalogue") + 1] + [os.path.join(d, "missing.yaml")] +
                                 cmd[cmd.index("--catalogue") + 2:], capture_output=True, text=True, env=env)
            self.assertEqual(bad.returncode, 2)
            self.assertIn("fragility_experiments: error: --catalogue", bad.stderr)


if __name__ == "__main__":
    unittest.main()
