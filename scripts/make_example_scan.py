#!/usr/bin/python3
"""make_example_scan: the example scan of docs/own_objects.md, docs/own_objects/urn_scan.ply (issue 43).

A lidded urn 420 mm tall as a phone or turntable scanner returns it: millimetres, 32-bit floats,
open at its base (the scanner never sees the bottom), 0.2 mm of noise, tilted 1.5 degrees, standing on
the turntable (a 10 mm disc, 400 mm across) that the scan also caught. Deterministic (seeded).

  make_example_scan.py [OUT.ply]
"""
import math
import os
import sys

import numpy as np
import meshio

# radius (mm) at height (mm): foot, belly, shoulder, neck, lip, lid
PROFILE = [(0, 70), (15, 78), (80, 118), (170, 140), (250, 128), (320, 80), (350, 62), (385, 66),
           (405, 78), (420, 0)]


def urn(segments=48, rings=40, rng=None):
    zs = np.linspace(0, 420, rings)
    rs = np.interp(zs, *zip(*PROFILE))
    t = 2 * math.pi * np.arange(segments) / segments
    v = [[r * math.cos(a), r * math.sin(a), z] for z, r in zip(zs[:-1], rs[:-1]) for a in t]
    v.append([0.0, 0.0, 420.0])  # the lid's centre
    f = []
    for i in range(rings - 2):
        for k in range(segments):
            a, b = i * segments + k, i * segments + (k + 1) % segments
            f += [(a, b, b + segments), (a, b + segments, a + segments)]
    top, ring = len(v) - 1, (rings - 2) * segments
    f += [(ring + k, ring + (k + 1) % segments, top) for k in range(segments)]
    v = np.array(v)
    v[:-1] += rng.normal(0, 0.2, size=(len(v) - 1, 3))  # scanner noise, mm
    v[:segments, 2] = np.clip(v[:segments, 2], 0, None)  # the foot rests on the turntable
    return v, np.array(f)  # open at the base: no bottom faces


def disc(radius=200, thickness=10, segments=64):
    t = 2 * math.pi * np.arange(segments) / segments
    v = [[radius * math.cos(a), radius * math.sin(a), z] for z in (-thickness, 0) for a in t]
    v += [[0, 0, -thickness], [0, 0, 0]]
    b, c = 2 * segments, 2 * segments + 1
    f = []
    for k in range(segments):
        n = (k + 1) % segments
        f += [(b, n, k), (c, segments + k, segments + n), (k, n, segments + n), (k, segments + n, segments + k)]
    return np.array(v, float), np.array(f)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "docs",
                                                                 "own_objects", "urn_scan.ply")
    rng = np.random.default_rng(43)
    uv, uf = urn(rng=rng)
    dv, df = disc()
    v = np.vstack([uv, dv])
    f = np.vstack([uf, df + len(uv)])
    tilt = math.radians(1.5)
    rot = np.array([[1, 0, 0], [0, math.cos(tilt), -math.sin(tilt)], [0, math.sin(tilt), math.cos(tilt)]])
    v = v @ rot.T + [120.0, -40.0, 35.0]  # the scanner's own origin
    meshio.Mesh(v.astype(np.float32), [("triangle", f.astype(np.int32))]).write(out, binary=True)
    print(f"{out}: {len(v)} vertices, {len(f)} triangles")


if __name__ == "__main__":
    main()
