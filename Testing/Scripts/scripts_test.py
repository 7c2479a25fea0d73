#!/usr/bin/env python3
"""Known answers for the benchmark scripts' own math (scripts/): the uncertainty fit
(fit_uncertainty.py: non-negative least squares, the quantile bound, pearson, the expected count
of pairs outside 85-95%) and the dense evaluation's point draw (dense_evaluation.py: true partners,
strata, area weights, segments, polyp clearance). The scripts measure the uncertainty figures in
docs/accuracy.md; a wrong fit or a wrong partner would show there as a model's fault. Needs numpy."""
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "Python"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from colonmap_testing import Checks  # noqa: E402
import dense_evaluation  # noqa: E402
import fit_uncertainty  # noqa: E402

checks = Checks()
check = checks.check

# Non-negative least squares: a negative true coefficient is held at 0, the others found.
rng = np.random.default_rng(3)
n = 4000
X = np.column_stack([np.ones(n), rng.random(n), rng.random(n), rng.random(n)])
y = X @ np.array([1.0, 0.5, 0.2, -0.3]) + 0.01 * rng.standard_normal(n)
c = fit_uncertainty.nonnegative_wls(X, y, np.ones(n), ridge=0.0)
check(c[3] == 0.0, f"the negative input is held at 0 (got {c[3]:.3f})")
check(abs(c[1] - 0.5) < 0.02 and abs(c[2] - 0.2) < 0.02, f"the others are found: {c[1]:.3f}, {c[2]:.3f}")
check(abs(c[0] - (1.0 - 0.15)) < 0.02, f"the intercept takes the dropped input's mean: {c[0]:.3f} (0.85)")
# The ridge shrinks the inputs, never the intercept: a constant is found whole.
c = fit_uncertainty.nonnegative_wls(X, np.full(n, 2.0), np.ones(n), ridge=1.0)
check(abs(c[0] - 2.0) < 1e-9 and np.abs(c[1:]).max() < 1e-9, f"a constant under a strong ridge: {np.round(c, 6)}")

# The quantile bound: errors whose log spread grows with one input and whose median grows with
# another. The bound covers tau of the points it was fitted on and of fresh ones, and widens with
# the spread's input more than the median does.
rng = np.random.default_rng(4)


def points(count):
    out = []
    for _ in range(count):
        a, b = rng.random(), rng.random()
        log_error = 0.5 + 1.0 * a + (0.1 + 0.6 * b) * rng.standard_normal()
        out.append({"x": [1.0, a, b], "error": math.exp(log_error), "polyp": False, "offset": 0.0})
    return out


fitted, fresh = points(6000), points(6000)
model = fit_uncertainty.fit(fitted, "quantile", tau=0.9)
for name, sample in (("fitted", fitted), ("fresh", fresh)):
    covered = np.mean([p["error"] <= fit_uncertainty.bound(model, p) for p in sample])
    check(abs(covered - 0.9) < 0.015, f"the bound covers 90% of the {name} points (got {covered:.3f})")
check(model["bound"][2] > model["coefficients"][2] + 0.5,
      f"the spread's input widens the bound ({model['bound'][2]:.2f}) more than the median ({model['coefficients'][2]:.2f})")
check(abs(model["coefficients"][1] - 1.0) < 0.1, f"the median follows its input (got {model['coefficients'][1]:.2f}, 1.0)")
check(abs(fit_uncertainty.pearson([1, 2, 3, 4], [2, 4, 6, 8.0]) - 1.0) < 1e-12, "pearson of a line is 1")
check(abs(fit_uncertainty.pearson([1, 2, 3, 4], [8, 6, 4, 2.0]) + 1.0) < 1e-12, "pearson of a falling line is -1")

# Pairs outside 85-95% for a bound blind to segment slides. One segment of 2000 points per pair,
# log(error / bound) = slide + residual, slide ~ N(0, 0.3), residual ~ N(0, 0.7): calibrated to 90%
# the offset is c = z90 sqrt(0.3^2 + 0.7^2); a pair is outside when its slide is above c - 0.7 z85
# or below c - 0.7 z95: 0.202 + 0.280 = 0.48 of the pairs. No slide: none outside.
rng = np.random.default_rng(5)


def held(slide_sd, size=2000, pairs=40):
    out = []
    for pair in range(pairs):
        slide = slide_sd * rng.standard_normal()
        out += [({"pool": "pool", "pair": f"pool/seed{pair}", "group": "A", "polyp": False, "error": math.exp(slide + 0.7 * z)}, 1.0, True)
                for z in rng.standard_normal(size)]
    return out


sliding = fit_uncertainty.slide_blind_misses(held(0.3), trials=200)
still = fit_uncertainty.slide_blind_misses(held(0.0), trials=200)
check(abs(sliding["expectedOutside"] / 40 - 0.48) < 0.1, f"slides of SD 0.3 put 48% of pairs outside (got {sliding['expectedOutside']} of 40)")
check(still["expectedOutside"] < 0.5, f"no slide, no pair outside ({still['expectedOutside']} of 40)")
check(abs(sliding["pools"]["pool"]["slideSd"] - 0.3) < 0.1 and abs(still["pools"]["pool"]["residualSd"] - 0.7) < 0.02,
      f"slide and residual spreads measured: {sliding['pools']['pool']['slideSd']}, {still['pools']['pool']['residualSd']}")
# 200 points a segment: their median scatters by sqrt(pi/2) 0.7 / sqrt(200) = 0.062 with no slide at all.
small = fit_uncertainty.slide_blind_misses(held(0.0, size=200), trials=50)
check(small["pools"]["pool"]["slideSd"] < 0.035, f"the medians' own scatter is not taken for slides ({small['pools']['pool']['slideSd']})")

# The dense draw on a tube given in two postures: the prone posture an affine map of the supine,
# so each point's true partner is that map of it (barycentric coordinates carry over). Around the
# tube the first 12 vertices span 270 degrees and the other 12 the last 90: three quarters of the
# wall's area. Vertices of even rings belong to A, of odd rings to T, from ring 90 on to none.
rng = np.random.default_rng(6)
rings, around, radius = 101, 24, 10.0
s = np.repeat(np.arange(rings, dtype=float), around)  # 1 mm rings, s = 0..100
step = np.where(np.arange(around) < 12, 1.5 * math.pi / 12, 0.5 * math.pi / 12)
angle = np.tile(np.concatenate([[0.0], np.cumsum(step)[:-1]]), rings)
supine = np.column_stack([radius * np.cos(angle), radius * np.sin(angle), s])
faces = []
for r in range(rings - 1):
    for k in range(around):
        a, b = r * around + k, r * around + (k + 1) % around
        faces += [[a, b, a + around], [b, b + around, a + around]]
faces = np.array(faces)
A = np.array([[0.0, -1.2, 0.1], [1.1, 0.0, 0.0], [0.0, 0.2, 0.9]])
t = np.array([5.0, -3.0, 40.0])
prone = supine @ A.T + t
letters = [None if v >= 90 else "A" if int(v) % 2 == 0 else "T" for v in s]
polyp = (np.array([radius, 0.0, 30.0]), 6.0)
count = 2000
sup, pro = dense_evaluation.sample_wall(supine, prone, faces, s, letters, (0.0, 100.0), [polyp], count, seed=5)
positions = np.array([x for _, _, x in sup])
partners = np.array([x for _, _, x in pro])
fields = [dense_evaluation.describe(d) for _, d, _ in sup]
drawn_s = np.array([float(f["s"]) for f in fields])
segments = [f["segment"] for f in fields]
check(np.abs(positions @ A.T + t - partners).max() < 1e-9, "every prone point is the true partner of its supine point")
check(np.abs(np.linalg.norm(positions[:, :2], axis=1) - radius).max() < 1.6, "the points lie on the wall")
check(all(np.linalg.norm(x - polyp[0]) > polyp[1] for x in positions), "no point within the polyp's clearance")
index = np.array([int(label[1:]) - 1 for label, _, _ in sup])
width = 100.0 / count  # 0.05 mm, narrower than a ring: a point lies on a face across its stratum
check(np.all(np.abs(drawn_s - (index + 0.5) * width) <= 1.0 + 0.5 * width), "each point on a face across its stratum")
coarse = dense_evaluation.sample_wall(supine, prone, faces, s, letters, (0.0, 100.0), [polyp], 40, seed=5)[0]
coarse_s = np.array([float(dense_evaluation.describe(d)["s"]) for _, d, _ in coarse])
coarse_index = np.array([int(label[1:]) - 1 for label, _, _ in coarse])
check(np.all((coarse_s >= (coarse_index + 0.1) * 2.5 - 1.0) & (coarse_s <= (coarse_index + 0.9) * 2.5 + 1.0)),
      "strata wider than a ring: each point from the faces whose centres lie in the middle 80% of its stratum")
wide = np.mod(np.arctan2(positions[:, 1], positions[:, 0]), 2 * math.pi) < 1.5 * math.pi
check(abs(wide.mean() - 0.75) < 0.04, f"area-weighted: three quarters of the points on three quarters of the wall ({wide.mean():.3f})")
frac = drawn_s - np.floor(drawn_s)
ring = np.floor(drawn_s).astype(int)
expected = [("A" if (r + (f > 0.5)) % 2 == 0 else "T") for r, f in zip(ring, frac)]
clear = (frac < 1 / 3) | (frac > 2 / 3)  # there the face's nearest vertex is on the nearer ring
check(all(seg == e for seg, e, ok in zip(segments, expected, clear) if ok), "a point's segment is its face's nearest vertex's")
check(abs(len(sup) - count * 0.897) < count * 0.02, f"points nearest an unnamed vertex are left out ({len(sup)} of {count})")
again = dense_evaluation.sample_wall(supine, prone, faces, s, letters, (0.0, 100.0), [polyp], count, seed=5)[0]
check(all(np.array_equal(x, z) for (_, _, x), (_, _, z) in zip(sup, again)), "the same seed draws the same points")
sys.exit(checks.finish())
