#!/usr/bin/env python3
"""How strongly the true supine -> prone map shears each segment's wall, against our error there
(issue 19; a benchmark, not a test). For each pair of registration_seeds.py caches, per segment:

  length:      the segment's supine length (mm, ColonPhantom's truth.json);
  dilatation:  the mean (and p90) over the true wall's triangles of K = sigma_max / sigma_min of
               the true map (truth.json): 1 for a map that only moves, bends and scales the wall
               evenly, more where it shears it;
  deformation: how much our map bent the segment (ColonRegistration's registration.json,
               uncertainty.deformationMm: the RMS of its 3D displacement beyond the segment's best
               rigid motion), what a pair without truth shows of the above;
  error:       the mean true error of the registration there (errors.json).

Then per cache and segment the Pearson correlation over the seeds of the dilatation with our
error, and over every segment of every pair given, that of log(1 + deformation / 10 mm) with the
log of our error (the uncertainty model's input, RegistrationUncertainty.h). Where a segment has no folds to match, the registration's map is close to conformal, so a
true map that shears the wall more is an error the pair gives no means to see (docs/accuracy.md,
the HuBMAP VHF sigmoid).

    python3 scripts/truth_shear.py [--runs runs] [--seeds 1-8] [--output F.json] CACHE ...
"""
import argparse
import json
import math
import os

from registration_seeds import SEGMENTS, harmonic_run, parse_seeds, pearson


def one_pair(cache, seed, runs):
    truth_path = os.path.join(cache, f"seed{seed}", "phantom", "truth.json")
    run = harmonic_run(cache, seed, runs)
    if run is None or not os.path.exists(truth_path):
        return None
    truth = json.load(open(truth_path))["segments"]
    errors = json.load(open(os.path.join(run, "errors.json")))["segments"]
    report = json.load(open(os.path.join(run, "registration.json")))["segments"]
    out = {}
    for s in SEGMENTS:
        if s not in truth or s not in errors:
            continue
        out[s] = {"lengthMm": truth[s]["supineLengthMm"], "dilatationMean": truth[s]["dilatation"]["mean"],
                  "dilatationP90": truth[s]["dilatation"]["p90"], "errorMean": errors[s]["error3D"]["mean"],
                  "deformationMm": report.get(s, {}).get("uncertainty", {}).get("deformationMm")}
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("caches", nargs="+", help="registration_seeds.py caches (CACHE/seed<N>)")
    ap.add_argument("--runs", default="runs", help="the registration runs' folder")
    ap.add_argument("--seeds", default="1-8", help="e.g. 1-8 or 1,3,5")
    ap.add_argument("--output", default=None)
    a = ap.parse_args()
    out = {}
    for cache in a.caches:
        pairs = {seed: p for seed in parse_seeds(a.seeds) if (p := one_pair(cache, seed, a.runs))}
        if not pairs:
            raise SystemExit(f"truth_shear.py: error: no pair with truth.json and errors.json in '{cache}'")
        rows = {}
        for s in SEGMENTS:
            v = [p[s] for p in pairs.values() if s in p]
            if not v:
                continue
            dil, err = [x["dilatationMean"] for x in v], [x["errorMean"] for x in v]
            rows[s] = {"pairs": len(v), "lengthMm": round(sum(x["lengthMm"] for x in v) / len(v), 1),
                       "dilatationMean": [round(min(dil), 2), round(max(dil), 2)],
                       "errorMean": [round(min(err), 2), round(max(err), 2)],
                       "pearsonDilatationError": None if (r := pearson(dil, err)) is None else round(r, 2)}
            print(f"{cache} {s}: length {rows[s]['lengthMm']:.0f} mm, true dilatation {min(dil):.2f}-{max(dil):.2f}, "
                  f"our error {min(err):.1f}-{max(err):.1f} mm, r {rows[s]['pearsonDilatationError']}")
        out[cache] = {"segments": rows, "pairs": pairs}
    segs = [x for c in out.values() for p in c["pairs"].values() for x in p.values() if x["deformationMm"] is not None]
    if len(segs) >= 3 and (r := pearson([math.log1p(x["deformationMm"] / 10.0) for x in segs], [math.log(max(x["errorMean"], 0.2)) for x in segs])) is not None:
        print(f"all caches: log(1 + deformation / 10 mm) against log error over {len(segs)} segments: r {r:.2f}")
        out["deformationErrorPearson"] = {"segments": len(segs), "r": r}
    if a.output:
        json.dump(out, open(a.output, "w"), indent=1)


if __name__ == "__main__":
    main()
