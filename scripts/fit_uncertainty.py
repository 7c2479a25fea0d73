#!/usr/bin/env python3
"""Fits the registration uncertainty model (Libs/Registration/RegistrationUncertainty.h) on pairs with
ground truth and says how it holds on pairs it was not fitted on (issue 20). A benchmark, not a test.

    fit_uncertainty.py --pool NAME=CACHE[:RUNS] [--pool ...] [--test NAME=CACHE[:RUNS] ...] [--output fit.json]

Each pool is a registration_seeds.py cache (CACHE/seed<N>/RUNS/harmonic/{errors.json,registration.json} or,
with its --work CACHE/RUNS, CACHE/RUNS/seed<N>/harmonic; RUNS defaults to "runs"), e.g. phantom0.5=/tmp/ph3 gca=/tmp/rc-gca-00020:runs2. The model is
log sigma = c . x with x = UncertaintyFeatures (the same 16 inputs as the C++), fitted by least squares
of log(max(true error, 0.2 mm)) on the evaluation wall points and polyps (polyps weighted by
--polyp-weight), coefficients but the intercept kept >= 0. The 90% bound: with --bound q90,
sigma * exp(q90), q90 the 90% quantile of the fit's log residuals; with --bound quantile (the
model in use), log bound90 = b . x by linear quantile regression (tau, --tau, 0.9 by default) of
the same, never below sigma. Used now: --bound quantile --polyp-weight 25 --tau 0.92 (a fit at 0.9
covered 88% of the points of pairs it was not fitted on; docs/accuracy.md).

Held back, two ways (no pair is ever in the fit that reports on it):
  seeds:   fit on the odd seeds of every pool, report on the even ones, and the other way round;
  sources: fit on all but one source (tube = the phantom pools; each real colon), report on it.
Per held-back pair: coverage of the 90% bound on wall points; pooled: polyps' coverage, Pearson of the
bound with the true error, and of the points more than 20 mm off the share with a bound above 20 mm or
reliable=false (reliable = the registration's own Trusted flag and the held-back bound within
--reliable-bound, as ColonRegistration --reliableBoundMm makes it).
The final coefficients are fitted on all --pool pairs; paste them into RegistrationUncertainty.cxx.
--test pools are never fitted on, not even by the final fit: the final model's figures on them are
the plainest held-back check (e.g. the tube at another deformation and other seeds).
inSamplePerPool is a reference, not a result: each pool fitted on its own pairs and reported on them.
heldBackSeeds.slideBlindMisses: how many pairs a bound calibrated on each pool but as blind to how
far each segment slid would leave outside 85-95% (slide_blind_misses).
Pools made by dense_evaluation.py (2000 points per pair) read the same way (NAME=CACHE:dense).
Needs numpy (Debian: python3-numpy).
"""
import argparse
import glob
import json
import math
import os
import re

import numpy as np

from registration_seeds import harmonic_run, pearson

FEATURES = ["1", "log1p(loo)", "log1p(near/10)", "log1p(corr)", "log K", "1-pathCorrelation", "droppedFraction",
            "1/(1+matchesPer100mm)", "exp(-flex/30)", "1-curvatureAgreement", "lengthMismatch", "curv", "untrusted", "log scale", "log1p(along/10)",
            "log1p(deformation/10)"]
POLYP_WEIGHT = 1.0  # --polyp-weight


def features(p, seg):
    K = p.get("UncertaintyDilatation", p.get("dilatation", 1.0))
    K = max(1.0, K) if math.isfinite(K) else 10.0
    return [1.0, math.log1p(max(0.0, p["UncertaintyLoo"])), math.log1p(max(0.0, p["UncertaintyNearMm"]) / 10.0),
            math.log1p(max(0.0, p["UncertaintyCorrectionMm"])), math.log(K), 1.0 - seg["pathCorrelation"],
            seg["droppedFraction"], 1.0 / (1.0 + seg["matchesPer100mm"]),
            math.exp(-max(0.0, p.get("UncertaintyFlexureMm", 1000.0)) / 30.0), 1.0 - seg.get("curvatureAgreement", 1.0),
            seg.get("lengthMismatch", 0.0), min(5.0, max(0.0, p.get("UncertaintyCurvature", 0.0))),
            0.0 if p.get("trusted", p.get("reliable", True)) else 1.0,
            min(3.0, max(-2.0, math.log(max(1e-6, p.get("UncertaintyScale", 1.0))))),
            math.log1p(max(0.0, p.get("UncertaintyAlongMm", 0.0)) / 10.0),
            math.log1p(max(0.0, seg["deformationMm"]) / 10.0)]


def load(pools):
    points = []
    for name, spec in pools:
        cache, _, runs = spec.partition(":")
        runs = runs or "runs"
        for folder in sorted(glob.glob(os.path.join(cache, "seed*"))):
            seed = int(re.search(r"seed(\d+)$", folder).group(1))
            run = harmonic_run(cache, seed, runs)
            if run is None:
                continue
            ev = os.path.join(run, "errors.json")
            reg = json.load(open(os.path.join(run, "registration.json")))["segments"]
            # Every input the model reads must be in the file: a registration written before an
            # input existed would enter the fit with it at 0 and quietly drop it.
            old = [x for x, v in reg.items() if "deformationMm" not in v.get("uncertainty", {})]
            if old:
                raise SystemExit(f"fit_uncertainty.py: error: '{run}/registration.json' has no deformationMm (segments "
                                 f"{', '.join(old)}): written by an older ColonRegistration; run it again")
            for p in json.load(open(ev))["points"]:
                seg = reg.get(p.get("mapSegment", p["group"]))
                if seg is None or "UncertaintyLoo" not in p:
                    continue
                points.append({"pool": name, "source": "tube" if name.startswith("phantom") else name, "seed": seed,
                               "pair": f"{name}/seed{seed}", "group": p["group"], "polyp": p["group"] == "polyps", "error": p["error3D"],
                               "x": features(p, seg["uncertainty"]), "reliable": p.get("reliable", True),
                               "trusted": p.get("trusted", p.get("reliable", True)),
                               "offset": p.get("offset", 0.0), "bound": p["uncertainty"]})
    return points


def quantile(v, q):
    v = np.sort(np.asarray(v, dtype=float))
    return float(v[min(len(v) - 1, max(0, int(math.ceil(q * len(v))) - 1))])


def nonnegative_wls(X, y, w, ridge=1e-3):
    """Weighted least squares, every coefficient but the intercept kept >= 0 (each input is built so
    that more of it means less evidence: a signal must never narrow the bound), by dropping the
    most negative one and refitting. X: points x inputs, y and w per point (numpy arrays)."""
    n = X.shape[1]
    active = list(range(n))
    total = w.sum()
    while True:
        Xa = X[:, active]
        Xw = Xa * w[:, None]
        A = Xw.T @ Xa
        A[np.arange(1, len(active)), np.arange(1, len(active))] += ridge * total
        sol = np.linalg.solve(A, Xw.T @ y)
        if len(active) == 1 or sol[1:].min() >= 0.0:
            break
        del active[1 + int(np.argmin(sol[1:]))]
    c = np.zeros(n)
    c[active] = sol
    return c


def target(p):
    return math.log(max(p["error"], 0.2))


def fit(points, bound_model="q90", tau=0.9, iterations=40):
    """The median model: least squares of log(max(error, 0.2 mm)) on wall points and polyps (the
    findings a reader carries). The bound: "q90" = the median times exp(the 90% quantile of the log
    residuals), one factor for every point; "quantile" = a model of its own for the 90% quantile of
    the log error (linear quantile regression by iteratively reweighted least squares, the same
    inputs and signs), so that inputs that spread the errors more than they raise their median
    widen the bound more."""
    X = np.array([p["x"] for p in points], dtype=float)
    y = np.array([target(p) for p in points])
    # Polyps are few (about 2% of the points) and sit where the wall bends: weighted up so that
    # the bound holds for them too, not only for the wall around them.
    pw = np.array([POLYP_WEIGHT if p["polyp"] else 1.0 for p in points])
    c = nonnegative_wls(X, y, pw)
    model = {"coefficients": c.tolist(), "q90": quantile(y - X @ c, 0.9), "points": len(points)}
    if bound_model == "quantile":
        d = c.copy()
        d[0] += model["q90"]
        for _ in range(iterations):
            r = y - X @ d
            w = pw * np.where(r > 0, tau, 1.0 - tau) / np.maximum(np.abs(r), 0.02)
            d = nonnegative_wls(X, y, w, ridge=1e-4)
        model["bound"] = d.tolist()
    return model


def bound(model, p):
    if "bound" in model:  # never below the median (RegistrationUncertainty.cxx)
        b90 = math.exp(max(sum(di * xi for di, xi in zip(model["bound"], p["x"])),
                           sum(ci * xi for ci, xi in zip(model["coefficients"], p["x"]))))
    else:
        b90 = math.exp(sum(ci * xi for ci, xi in zip(model["coefficients"], p["x"])) + model["q90"])
    return math.sqrt(b90 * b90 + 0.25 * p["offset"] ** 2)  # PointTransfer's re-attachment term


def held_back(model, p, reliable_bound):
    """(point, bound, reliable) as the registration would write them with this model."""
    b = bound(model, p)
    return p, b, p["trusted"] and b <= reliable_bound


def report(held):
    """held: (point, bound, reliable) of held-back points."""
    pairs = {}
    for p, b, _ in held:
        if not p["polyp"]:
            pairs.setdefault(p["pair"], []).append(p["error"] <= b)
    wall = [(p, b, r) for p, b, r in held if not p["polyp"]]
    polyps = [(p, b, r) for p, b, r in held if p["polyp"]]
    large = [(p, b, r) for p, b, r in wall if p["error"] > 20.0]
    coverage = {k: round(sum(v) / len(v), 3) for k, v in sorted(pairs.items())}
    return {"coveragePerPair": coverage,
            "pairsWithin85to95": sum(0.85 <= c <= 0.95 for c in coverage.values()), "pairs": len(coverage),
            "coverageMin": min(coverage.values()), "coverageMax": max(coverage.values()),
            "wallCoverage": round(sum(p["error"] <= b for p, b, _ in wall) / len(wall), 3),
            "polypCoverage": round(sum(p["error"] <= b for p, b, _ in polyps) / len(polyps), 3) if polyps else None,
            "pearson": round(pearson([b for _, b, _ in wall], [p["error"] for p, _, _ in wall]), 3),
            "above20mm": len(large),
            "above20mmWarned": sum(b > 20.0 or not r for _, b, r in large),
            "above20mmUnreliable": sum(not r for _, _, r in large),
            "above20mmUntrusted": sum(not p["trusted"] for p, _, _ in large),
            "above20mmMissedByPool": {k: sum(1 for p, b, r in large if p["pair"].split("/")[0] == k and b <= 20.0 and r)
                                      for k in sorted({p["pair"].split("/")[0] for p, _, _ in large})},
            "unreliableFraction": round(sum(not r for _, _, r in wall) / len(wall), 3),
            "unreliableByPool": {k: round(sum(not r for p, _, r in wall if p["pair"].split("/")[0] == k) /
                                          max(1, sum(1 for p, _, _ in wall if p["pair"].split("/")[0] == k)), 3)
                                 for k in sorted({p["pair"].split("/")[0] for p, _, _ in wall})},
            "untrustedFraction": round(sum(not p["trusted"] for p, _, _ in wall) / len(wall), 3)}


def slide_blind_misses(held, trials=1000, seed=1):
    """How many held-back pairs would fall outside 85-95% for a bound calibrated on each pool but as
    blind as this one to how far each segment slid (a segment's points share most of their error):
    an expectation for comparison, not a floor (a better model would leave smaller slides).
    Per pool: a segment's slide = the median over its wall points of log(error / bound), less the
    pool's mean, shrunk by the median's own sampling variance (pi/2 x residual variance / points,
    which the re-draw below adds back); a point's residual = its log(error / bound) less its
    segment's median. Pairs are re-drawn with their segments' sizes, each segment a random slide of
    the pool plus random point residuals, the offset set so that the pool covers 90%.
    held: (point, bound, reliable). Returns per pool and in all the expected count and its SD."""
    rng = np.random.default_rng(seed)
    segments = {}  # (pool, pair, segment) -> log(error / bound) of its wall points
    for p, b, _ in held:
        if not p["polyp"]:
            segments.setdefault((p["pool"], p["pair"], p["group"]), []).append(math.log(max(p["error"], 0.2) / b))
    pools, outside = {}, np.zeros(trials)
    for pool in sorted({k[0] for k in segments}):
        keys = [k for k in segments if k[0] == pool]
        medians = np.array([np.median(segments[k]) for k in keys])
        residuals = np.concatenate([np.array(segments[k]) - m for k, m in zip(keys, medians)])
        sampling = math.pi / 2 * residuals.var() * np.mean([1.0 / len(segments[k]) for k in keys])
        slides = (medians - medians.mean()) * math.sqrt(max(0.0, 1.0 - sampling / max(medians.var(), 1e-12)))
        sizes = {}  # pair -> its segments' point counts
        for k in keys:
            sizes.setdefault(k[1], []).append(len(segments[k]))
        pairs = sorted(sizes)
        # The offset: the 90% quantile of slide + residual (4000 x 25 draws: +-0.01 on the quantile).
        offset = float(np.quantile(slides[rng.integers(len(slides), size=4000)][:, None] +
                                   residuals[rng.integers(len(residuals), size=(4000, 25))], 0.9))
        # Each trial re-draws every pair of the pool once.
        count = np.zeros(trials)
        for t in range(trials):
            for pair in pairs:
                n = sizes[pair]
                covered = sum(np.count_nonzero(slides[rng.integers(len(slides))] +
                                               residuals[rng.integers(len(residuals), size=k)] <= offset) for k in n)
                count[t] += not 0.85 <= covered / sum(n) <= 0.95
        outside += count
        pools[pool] = {"pairs": len(pairs), "slideSd": round(float(slides.std()), 3),
                       "residualSd": round(float(residuals.std()), 3),
                       "expectedOutside": round(float(count.mean()), 2)}
    return {"pools": pools, "expectedOutside": round(float(outside.mean()), 1), "sd": round(float(outside.std()), 1)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pool", action="append", required=True, help="NAME=CACHE[:RUNS]")
    ap.add_argument("--test", action="append", default=[],
                    help="NAME=CACHE[:RUNS] pairs never fitted on (not even by the final fit): reported with the final model")
    ap.add_argument("--output", default=None)
    ap.add_argument("--reliable-bound", type=float, default=7.0,
                    help="ColonRegistration --reliableBoundMm: reliable = trusted and bound <= this (mm)")
    ap.add_argument("--bound", choices=("q90", "quantile"), default="q90",
                    help="the bound's model: the median's times one factor, or a quantile regression of its own")
    ap.add_argument("--drop", default="", help="inputs left out of the model, comma-separated names of FEATURES")
    ap.add_argument("--polyp-weight", type=float, default=1.0, help="weight of a polyp against a wall point in the fits")
    ap.add_argument("--tau", type=float, default=0.9,
                    help="the quantile the bound's regression fits (--bound quantile): above 0.9 where a fit "
                         "covers fewer than 90%% of the points it was not fitted on")
    a = ap.parse_args()
    global POLYP_WEIGHT
    POLYP_WEIGHT = a.polyp_weight
    points = load([tuple(s.split("=", 1)) for s in a.pool])
    tests = load([tuple(s.split("=", 1)) for s in a.test])
    for name in filter(None, a.drop.split(",")):
        i = FEATURES.index(name)
        for p in points + tests:
            p["x"][i] = 0.0
    out = {"features": FEATURES, "pools": a.pool,
           "options": {"bound": a.bound, "tau": a.tau, "polypWeight": a.polyp_weight, "reliableBound": a.reliable_bound}}
    # Held back by seed parity.
    held = []
    for parity in (1, 0):
        m = fit([p for p in points if p["seed"] % 2 == parity], a.bound, a.tau)
        held += [held_back(m, p, a.reliable_bound) for p in points if p["seed"] % 2 != parity]
    out["heldBackSeeds"] = report(held)
    out["heldBackSeeds"]["slideBlindMisses"] = slide_blind_misses(held)
    # Held back by source.
    out["heldBackSources"] = {}
    for s in sorted({p["source"] for p in points}):
        rest = [p for p in points if p["source"] != s]
        if not rest:
            continue
        m = fit(rest, a.bound, a.tau)
        out["heldBackSources"][s] = report([held_back(m, p, a.reliable_bound) for p in points if p["source"] == s])
    # A reference, not a result: each pool fitted on its own pairs and reported on them (the pairs are
    # in their own fit; it does not maximise the pairs in range, so it is no upper bound either).
    in_sample = []
    for name in sorted({p["pool"] for p in points}):
        own = [p for p in points if p["pool"] == name]
        m = fit(own, a.bound, a.tau)
        in_sample += [held_back(m, p, a.reliable_bound) for p in own]
    out["inSamplePerPool"] = report(in_sample)
    # The current model, as the registration wrote it (for comparison).
    out["asWritten"] = report([(p, p["bound"], p["reliable"]) for p in points])
    final = fit(points, a.bound, a.tau)
    out["final"] = {"coefficients": [round(c, 4) for c in final["coefficients"]], "q90": round(final["q90"], 4),
                    "bound": [round(d, 4) for d in final["bound"]] if "bound" in final else None,
                    "points": final["points"],
                    "onItsOwnFit": report([held_back(final, p, a.reliable_bound) for p in points])}
    if tests:
        out["testPairs"] = report([held_back(final, p, a.reliable_bound) for p in tests])
    text = json.dumps(out, indent=1)
    if a.output:
        open(a.output, "w").write(text + "\n")
    for k in ("heldBackSeeds", "inSamplePerPool", "asWritten", "testPairs"):
        if k not in out:
            continue
        r = out[k]
        outside = ", ".join(f"{pair} {c}" for pair, c in r["coveragePerPair"].items() if not 0.85 <= c <= 0.95)
        print(f"{k}: pairs in 85-95% {r['pairsWithin85to95']}/{r['pairs']} (min {r['coverageMin']}, max {r['coverageMax']}), "
              f"wall {r['wallCoverage']}, polyps {r['polypCoverage']}, r {r['pearson']}, "
              f">20 mm warned {r['above20mmWarned']}/{r['above20mm']} (unreliable {r['above20mmUnreliable']}, "
              f"untrusted {r['above20mmUntrusted']}), unreliable {r['unreliableFraction']}, untrusted {r['untrustedFraction']}"
              + (f"; outside: {outside}" if outside else ""))
    blind = out["heldBackSeeds"]["slideBlindMisses"]
    print(f"  pairs outside 85-95% expected of a bound calibrated per pool, as blind to segment slides as this one: "
          f"{blind['expectedOutside']} +- {blind['sd']} of {out['heldBackSeeds']['pairs']} (" +
          ", ".join(f"{k} {v['expectedOutside']} of {v['pairs']}, slide SD {v['slideSd']}" for k, v in blind["pools"].items()) + ")")
    for s, r in out["heldBackSources"].items():
        print(f"  held-back source {s}: pairs in 85-95% {r['pairsWithin85to95']}/{r['pairs']} (min {r['coverageMin']}, "
              f"max {r['coverageMax']}), wall {r['wallCoverage']}, polyps {r['polypCoverage']}, r {r['pearson']}, "
              f">20 warned {r['above20mmWarned']}/{r['above20mm']}, unreliable {r['unreliableFraction']}")
    print("final: constexpr double kC[kUncertaintyFeatures] = {" + ", ".join(f"{c:.4f}" for c in out["final"]["coefficients"]) +
          "};  kLogQ90 = " + f"{out['final']['q90']:.4f}")
    if out["final"]["bound"]:
        print("final: constexpr double kB[kUncertaintyFeatures] = {" + ", ".join(f"{d:.4f}" for d in out["final"]["bound"]) + "};")


if __name__ == "__main__":
    main()
