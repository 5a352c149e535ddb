#!/usr/bin/python3
"""rocking_report's numbers from independent sources: the spectrum recursion against the closed-form
response of a damped oscillator, and each catalogue item's Housner period against rocking_sim's body
(the core's geometry). argv[1] = scripts/rocking_report, argv[2] = rocking_sim, argv[3] = a catalogue."""
import importlib.machinery
import importlib.util
import json
import math
import subprocess
import sys
import unittest

import numpy as np
import yaml

TOOL, SIM, CATALOGUE = sys.argv[1:4]
loader = importlib.machinery.SourceFileLoader('rocking_report', TOOL)
spec = importlib.util.spec_from_loader('rocking_report', loader)
report = importlib.util.module_from_spec(spec)
loader.exec_module(report)


class Spectrum(unittest.TestCase):
    def test_step_response_peak_is_the_closed_form(self):
        # a_g = a0 from t = 0 (oscillator at rest): x(t) = -a0/w^2 (1 - e^{-z w t}(cos wd t + z/sqrt(1-z^2) sin wd t)),
        # whose peak |x| = a0/w^2 (1 + exp(-z pi / sqrt(1 - z^2))) is at t = pi / wd.
        z, a0 = 0.05, 2.0
        for T in (0.1, 0.5, 2.0):
            dt = T / 20000.0
            acc = np.full(int(1.5 * T / dt), a0)
            w = 2 * math.pi / T
            exact = a0 / w ** 2 * (1 + math.exp(-z * math.pi / math.sqrt(1 - z * z)))
            self.assertAlmostEqual(report.nigam_jennings(acc, dt, [T])[0] / exact, 1.0, delta=1e-7, msg=T)

    def test_linear_in_the_input_and_rigid_limit_is_pga(self):
        # Linearity: doubling the input doubles the peak (same recursion), and a
        # rigid oscillator (T -> 0) follows the ground: PSA -> PGA.
        t = np.arange(0, 4, 0.005)
        acc = 3.0 * np.sin(2 * math.pi * 1.3 * t)
        T = np.array([0.01, 0.7])
        one, two = report.nigam_jennings(acc, 0.005, T), report.nigam_jennings(2 * acc, 0.005, T)
        np.testing.assert_allclose(two, 2 * one, rtol=1e-12)
        self.assertAlmostEqual((2 * math.pi / 0.01) ** 2 * one[0] / 3.0, 1.0, delta=0.01)


class HousnerPeriods(unittest.TestCase):
    def test_periods_equal_the_core_body(self):
        with open(CATALOGUE) as f:
            items = yaml.safe_load(f)['items']
        checked = 0
        for e in items:
            got = report.item_periods(e)
            args = [SIM, '--record', sys.argv[4], '--json', '--width', str(report.nominal(e['width'])),
                    '--cg-height', str(report.nominal(e['cg_height'])),
                    '--eccentricity', str(report.nominal(e.get('eccentricity', 0.5)))]
            if 'radius_of_gyration' in e:
                args += ['--radius-of-gyration', str(report.nominal(e['radius_of_gyration']))]
            elif e.get('shape') == 'cylinder':  # solid cylinder, diameter B, height 2h, about a diameter
                b, h = report.nominal(e['width']), report.nominal(e['cg_height'])
                args += ['--radius-of-gyration', repr(math.sqrt((3 * (b / 2) ** 2 + (2 * h) ** 2) / 12))]
                if 'depth' in e:
                    d = report.nominal(e['depth'])
                    args += ['--radius-of-gyration-y', repr(math.sqrt((3 * (d / 2) ** 2 + (2 * h) ** 2) / 12))]
            if 'depth' in e:
                args += ['--depth', str(report.nominal(e['depth'])), '--eccentricity-y', str(report.nominal(e.get('eccentricity_y', 0.5)))]
            out = json.loads(subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=True).stdout)
            for plane in got:
                body = out['planes'][plane]['body']
                p = body['p1_radps'] if body['alpha1_rad'] <= body['alpha2_rad'] else body['p2_radps']
                self.assertAlmostEqual(got[plane], 2 * math.pi / p, delta=1e-9 * got[plane], msg='%s %s' % (e['id'], plane))
                checked += 1
        self.assertGreaterEqual(checked, 10)


if __name__ == '__main__':
    unittest.main(argv=[sys.argv[0]], verbosity=2)
