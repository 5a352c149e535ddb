#!/usr/bin/python3
"""Writes a synthetic catalogue of N items (for load tests of the live monitor).

Usage: make_catalogue.py N OUT.yaml [--topic /ground/imu] [--frame accelerometer] [--seed 1] [--single-plane]
Items get random but plausible geometry (B 0.15-0.8 m, depth D 0.15-1.0 m, h 0.2-1.2 m, nu1 and
eccentricity_y 0.25-0.5, mu_s 0.3-0.8) and random yaw, all fed by one Imu sensor. --single-plane
leaves the depth out (items rocking in their x-z plane only). --uncertain gives mu_s and cg_height as
laws (the node then runs an ensemble per item).
"""
import argparse
import math
import random

p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
p.add_argument("n", type=int)
p.add_argument("out")
p.add_argument("--topic", default="/ground/imu")
p.add_argument("--frame", default="accelerometer")
p.add_argument("--seed", type=int, default=1)
p.add_argument("--rate", type=float, default=200.0)
p.add_argument("--single-plane", action="store_true", help="no depth: x-z plane only")
p.add_argument("--uncertain", action="store_true",
               help="mu_s uniform +-0.1 and cg_height normal (sd 4 %%) around the drawn values: ensembles")
p.add_argument("--solid", action="store_true",
               help="also the 3-D description of each item (a homogeneous box on its four corners)")
a = p.parse_args()
rng = random.Random(a.seed)
with open(a.out, "w") as f:
    f.write("# %d synthetic items (scripts/make_catalogue.py, seed %d)\n" % (a.n, a.seed))
    f.write("sensors:\n  - {name: floor, topic: %s, type: imu, rate: %g}\nitems:\n" % (a.topic, a.rate))
    for i in range(a.n):
        h = rng.uniform(0.2, 1.2)
        b = rng.uniform(0.15, min(0.8, 1.5 * h))
        # The second plane's numbers are drawn after the first's, so --single-plane keeps the same widths.
        nu, mu, x, y, yaw = (rng.uniform(0.25, 0.5), rng.uniform(0.3, 0.8), rng.uniform(0, 50),
                             rng.uniform(0, 50), rng.uniform(-math.pi, math.pi))
        d, nu_y = rng.uniform(0.15, min(1.0, 1.5 * h)), rng.uniform(0.25, 0.5)
        depth = "" if a.single_plane else "depth: %.3f, eccentricity_y: %.2f, " % (d, nu_y)
        if a.uncertain:
            hv = "{normal: [%.3f, %.4f]}" % (h, 0.04 * h)
            muv = "{uniform: [%.2f, %.2f], nominal: %.2f}" % (max(0.05, mu - 0.1), mu + 0.1, mu)
        else:
            hv, muv = "%.3f" % h, "%.2f" % mu
        solid = ""
        if a.solid:
            dd = 0.5 * b if a.single_plane else d
            ny = 0.5 if a.single_plane else nu_y
            solid = ("mass: 1.0, centre_of_mass: [%.6f, %.6f, %.3f], central_inertia: [[%.6g, 0, 0], [0, %.6g, 0], "
                     "[0, 0, %.6g]], base_polygon: [[0, 0], [%.3f, 0], [%.3f, %.3f], [0, %.3f]], " % (
                         nu * b, ny * dd, h, (dd * dd + 4 * h * h) / 12, (b * b + 4 * h * h) / 12,
                         (b * b + dd * dd) / 12, b, b, dd, dd))
        f.write("  - {id: item%05d, sensor: floor, width: %.3f, %scg_height: %s, eccentricity: %.2f, "
                "mu_s: %s, %spose: {parent_frame: %s, x: %.2f, y: %.2f, yaw: %.3f}}\n" % (
                    i, b, depth, hv, nu, muv, solid, a.frame, x, y, yaw))
