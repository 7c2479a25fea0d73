#!/usr/bin/env python3
"""Known answers for the benchmark scripts' own math (scripts/): the uncertainty fit
(fit_uncertainty.py: non-negative least squares, the quantile bound, pearson) and the dense
evaluation's point draw (dense_evaluation.py: true partners, strata, segments, polyp clearance).
The scripts measure the uncertainty figures in docs/accuracy.md; a wrong fit or a wrong partner
would show there as a model's fault. Needs numpy."""
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
rng = np.random.default_rng(3)

# Non-negative least squares: a negative true coefficient is held at 0, the others found.
n = 4000
X = np.column_stack([np.ones(n), rng.random(n), rng.random(n), rng.random(n)])
y = X @ np.array([1.0, 0.5, 0.2, -0.3]) + 0.01 * rng.standard_normal(n)
c = fit_uncertainty.nonnegative_wls(X, y, np.ones(n), ridge=0.0)
check(c[3] == 0.0, f"the negative input is held at 0 (got {c[3]:.3f})")
check(abs(c[1] - 0.5) < 0.02 and abs(c[2] - 0.2) < 0.02, f"the others are found: {c[1]:.3f}, {c[2]:.3f}")
check(abs(c[0] - (1.0 - 0.15)) < 0.02, f"the intercept takes the dropped input's mean: {c[0]:.3f} (0.85)")

# The quantile bound: errors whose log spread grows with one input and whose median grows with
# another. The bound covers tau of the points it was fitted on and of fresh ones, and widens with
# the spread's input more than the median does.
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

# The floor of pairs outside 85-95%: none when segments do not slide (1000 points per pair), most
# when each segment's points share a large slide.
def held(slide_sd):
    out = []
    for pair in range(10):
        for segment in "ATDS":
            slide = slide_sd * rng.standard_normal()
            for _ in range(250):
                error = math.exp(slide + 0.7 * rng.standard_normal())
                out.append(({"pair": f"pool/seed{pair}", "group": segment, "polyp": False, "error": error}, 2.5, True))
    return out


still = fit_uncertainty.unseen_slide_floor(held(0.0), trials=300)
sliding = fit_uncertainty.unseen_slide_floor(held(1.0), trials=300)
check(still["expectedOutside"] < 0.3, f"no slide, no pair outside ({still['expectedOutside']} of 10)")
check(sliding["expectedOutside"] > 5, f"large slides put most pairs outside ({sliding['expectedOutside']} of 10)")
check(abs(sliding["pool"]["slideSd"] - 1.0) < 0.45 and abs(still["pool"]["residualSd"] - 0.7) < 0.05,
      f"slide and residual spreads measured: {sliding['pool']['slideSd']}, {still['pool']['residualSd']}")

# The dense draw on a tube given in two postures: the prone posture an affine map of the supine,
# so each point's true partner is that map of it (barycentric coordinates carry over).
rings, around, radius = 101, 24, 10.0
s = np.repeat(np.arange(rings, dtype=float), around)  # 1 mm rings, s = 0..100
angle = np.tile(np.arange(around) * 2 * math.pi / around, rings)
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
letters = ["A" if v < 50 else "T" if v < 90 else None for v in s]
polyp = (np.array([radius, 0.0, 30.0]), 6.0)
count = 400
sup, pro = dense_evaluation.sample_wall(supine, prone, faces, s, letters, (0.0, 100.0), [polyp], count, seed=5)
positions = np.array([x for _, _, x in sup])
partners = np.array([x for _, _, x in pro])
check(np.abs(positions @ A.T + t - partners).max() < 1e-9, "every prone point is the true partner of its supine point")
check(np.abs(np.linalg.norm(positions[:, :2], axis=1) - radius).max() < 0.3, "the points lie on the wall")
check(all(np.linalg.norm(x - polyp[0]) > polyp[1] for x in positions), "no point within the polyp's clearance")
drawn_s = np.array([float(dict(kv.split("=") for kv in d.split())["s"]) for _, d, _ in sup])
index = np.array([int(label[1:]) - 1 for label, _, _ in sup])
check(np.all(np.abs(drawn_s - (index + 0.5) * 100.0 / count) <= 0.5 * 100.0 / count + 1.0),
      "each point lies in its stratum along the colon (within a ring)")
segments = [dict(kv.split("=") for kv in d.split())["segment"] for _, d, _ in sup]
check(set(segments) == {"A", "T"}, f"segments as the vertices name them, none where unnamed: {sorted(set(segments))}")
check(all((seg == "A") == (v < 50.5) for seg, v in zip(segments, drawn_s) if abs(v - 50) > 1),
      "a point's segment is its nearest vertex's")
check(abs(len(sup) - count * 0.9) < count * 0.03, f"the unnamed tenth is left out ({len(sup)} of {count})")
again = dense_evaluation.sample_wall(supine, prone, faces, s, letters, (0.0, 100.0), [polyp], count, seed=5)[0]
check(all(np.array_equal(x, z) for (_, _, x), (_, _, z) in zip(sup, again)), "the same seed draws the same points")
sys.exit(checks.finish())
