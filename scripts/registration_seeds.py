#!/usr/bin/env python3
"""The issue-7 measurement: registration accuracy over several phantom seeds, on surfaces from
our own CT pipeline (phantom CT -> cleansing -> segmentation -> surface -> landmarks ->
flattening), for each registration method (conformal map only, centerline arc length,
harmonic), evaluated against the phantom's exact truth.

    registration_seeds.py --cli-dir DIR --cache CACHE [--seeds 1-10] [--spacing 0.7,0.7,1.0]
                          [--methods none,conformal,centerline,harmonic[,harmonic-affine]] [--output seeds.json]
                          [--real-colon ATLAS_DIR] [--deformation 0.5] [--prepare-only] [--keep-volumes]

--real-colon makes each pair with ColonPhantom --realColon ATLAS_DIR (issue 17: a real colon under the
seeded deformation) instead of the tube. Method "none" is no registration: the supine position of each
evaluation point taken as its prone position (the baseline a registration must beat). A pair whose
pipeline stops (a stage exits non-zero) is reported with the stage and its error line, not hidden.

CACHE/seed<N>/ holds, per seed, what the registration needs and is made once when missing:
phantom/ (truth files only: *_eval.mrk.json, *_polyps.mrk.json, truth.json, *_truth.vtp;
the CT and label volumes are deleted after the pair is done unless --keep-volumes),
surface/, landmarks/{supine,prone}/, flattening/{supine,prone}/. Then per seed and method:
ColonRegistration, ColonEvaluateRegistration (wall points and polyps, per segment, the
supine -> prone -> supine round trip, each point's uncertainty as ColonTransferPoints gives it). Writes one
JSON: per seed, per method (ColonEvaluateRegistration's report: overall and per segment
mean/median/p90/max, polyps, round trip, uncertainty; flips, times) and the aggregate over seeds
(all seeds' evaluation points pooled, per segment pooled, per-seed figures and the worst seed,
the Pearson/Spearman correlation of ColonTransferPoints' uncertainty with the true error).
This is a benchmark, not a test. --dump-points FILE also writes every point's error and flat
positions (for diagnosis).
"""
import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

SEGMENTS = "ATDSR"


def run(cli, module, args, log=None):
    exe = os.path.join(cli, module)
    with tempfile.NamedTemporaryFile("r", suffix=".txt") as ret:
        start = time.time()
        r = subprocess.run([exe, "--returnparameterfile", ret.name] + args, text=True,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        seconds = time.time() - start
        if r.returncode != 0:
            raise RuntimeError(f"{module} {' '.join(args)} failed: {r.stderr.strip()}")
        values = dict(re.findall(r"^(\w+) = (.*)$", open(ret.name).read(), re.M))
    if log:
        print(f"  {module}: {seconds:.1f} s", file=log, flush=True)
    return values, seconds


def parse_seeds(text):
    seeds = []
    for part in text.split(","):
        if "-" in part:
            a, b = part.split("-")
            seeds += list(range(int(a), int(b) + 1))
        else:
            seeds.append(int(part))
    return seeds


def landmarks_and_flattening(cli, folder):
    """ColonLandmarks on both surfaces at once (flexures chosen jointly), then ColonFlattening."""
    for sub in ("landmarks", "flattening"):
        shutil.rmtree(os.path.join(folder, sub), ignore_errors=True)
        os.makedirs(os.path.join(folder, sub), exist_ok=True)
    surface = {scan: os.path.join(folder, "surface", f"{scan}_surface.vtp") for scan in ("supine", "prone")}
    landmarks = {scan: os.path.join(folder, "landmarks", scan) for scan in ("supine", "prone")}
    run(cli, "ColonLandmarks", [surface["supine"], landmarks["supine"], "--pairedSurface", surface["prone"],
                                "--pairedOutputDirectory", landmarks["prone"], "--scanNames", "supine,prone"],
        sys.stdout)
    for scan in ("supine", "prone"):
        run(cli, "ColonFlattening", [landmarks[scan], os.path.join(folder, "flattening", scan)], sys.stdout)


def prepare(cli, folder, seed, spacing, keep_volumes, real_colon=None, deformation=None, redo_landmarks=False):
    """Makes CACHE/seed<N> (phantom truth, surfaces, landmarks, flattenings) when missing."""
    surfaces = [os.path.join(folder, "surface", f"{s}_surface.vtp") for s in ("supine", "prone")]
    if redo_landmarks and all(os.path.exists(f) for f in surfaces):
        print(f"seed {seed}: landmarks and flattening again from the cached surfaces", flush=True)
        landmarks_and_flattening(cli, folder)
        return
    if all(os.path.exists(os.path.join(folder, "flattening", s, "flattening.json")) for s in ("supine", "prone")):
        return
    print(f"seed {seed}: making the pair in {folder}", flush=True)
    phantom = os.path.join(folder, "phantom")
    args = ["--outputDirectory", phantom, "--seed", str(seed), "--spacing", spacing]
    if real_colon:
        args += ["--realColon", real_colon]
    if deformation is not None:
        args += ["--deformation", str(deformation)]
    run(cli, "ColonPhantom", args, sys.stdout)
    work = os.path.join(folder, "work")
    for sub in ("work", "surface"):
        os.makedirs(os.path.join(folder, sub), exist_ok=True)
    for scan in ("supine", "prone"):
        ct = os.path.join(phantom, f"{scan}.nrrd")
        cleansed = os.path.join(work, f"{scan}_cleansed.nrrd")
        lumen = os.path.join(work, f"{scan}_lumen.nrrd")
        surface = os.path.join(folder, "surface", f"{scan}_surface.vtp")
        run(cli, "ColonCleansing", [ct, cleansed], sys.stdout)
        run(cli, "ColonSegmentation", [cleansed, lumen], sys.stdout)
        run(cli, "ColonSurface", [lumen, surface, "--referenceCT", cleansed], sys.stdout)
        if not keep_volumes:
            for f in (cleansed, lumen):
                os.remove(f)
    landmarks_and_flattening(cli, folder)
    if not keep_volumes:
        shutil.rmtree(work, ignore_errors=True)
        for scan in ("supine", "prone"):
            os.remove(os.path.join(phantom, f"{scan}.nrrd"))


def pearson(a, b):
    if len(a) < 3:
        return None
    ma, mb = statistics.fmean(a), statistics.fmean(b)
    sa = math.sqrt(sum((x - ma) ** 2 for x in a))
    sb = math.sqrt(sum((y - mb) ** 2 for y in b))
    if sa == 0 or sb == 0:
        return None
    return sum((x - ma) * (y - mb) for x, y in zip(a, b)) / (sa * sb)


def spearman(a, b):
    def ranks(v):
        order = sorted(range(len(v)), key=lambda i: v[i])
        r = [0.0] * len(v)
        for k, i in enumerate(order):
            r[i] = float(k)
        return r
    return pearson(ranks(a), ranks(b)) if len(a) >= 3 else None


def stats(values):
    if not values:
        return None
    v = sorted(values)
    p90 = v[min(len(v) - 1, int(math.ceil(0.9 * len(v))) - 1)]
    return {"count": len(v), "mean": round(statistics.fmean(v), 3), "median": round(statistics.median(v), 3),
            "p90": round(p90, 3), "max": round(v[-1], 3)}


def harmonic_run(cache, seed, runs="runs"):
    """The harmonic registration folder of a cached pair: CACHE/seed<N>/RUNS/harmonic (the default) or
    CACHE/RUNS/seed<N>/harmonic (--work CACHE/RUNS); None when neither holds an errors.json."""
    for f in (os.path.join(cache, f"seed{seed}", runs, "harmonic"), os.path.join(cache, runs, f"seed{seed}", "harmonic")):
        if os.path.exists(os.path.join(f, "errors.json")):
            return f
    return None


def markup_points(path):
    doc = json.load(open(path))
    return {p["label"]: (p["position"], p.get("description", "")) for p in doc["markups"][0]["controlPoints"]}


def no_registration(folder):
    """The baseline: each evaluation point's supine position taken as its prone position."""
    phantom = os.path.join(folder, "phantom")
    sup = markup_points(os.path.join(phantom, "supine_eval.mrk.json"))
    pro = markup_points(os.path.join(phantom, "prone_eval.mrk.json"))
    points, segs = [], {}
    for label, (p, desc) in sup.items():
        q = pro[label][0]
        seg = re.search(r"segment=(\w)", desc).group(1)
        e = math.dist(p, q)
        points.append({"label": label, "group": seg, "error3D": e, "uncertainty": 0.0})
        segs.setdefault(seg, []).append(e)
    psup = markup_points(os.path.join(phantom, "supine_polyps.mrk.json"))
    ppro = markup_points(os.path.join(phantom, "prone_polyps.mrk.json"))
    polyp = [math.dist(p, ppro[k][0]) for k, (p, _) in psup.items()]
    ev = {"overall": {"error3D": stats([pt["error3D"] for pt in points]), "roundTrip": {"mean": 0.0}},
          "segments": {k: {"error3D": stats(v)} for k, v in segs.items()}}
    if polyp:
        ev["polyps"] = {"error3D": stats(polyp)}
    return {"registrationSeconds": 0.0, "returns": {}, "evaluation": ev, "roundTripMeanMm": 0.0,
            "uncertaintyPearson": None, "uncertaintySpearman": None, "points": points}


def evaluate(cli, folder, method, out):
    if method == "none":
        return no_registration(folder)
    flat = os.path.join(folder, "flattening")
    phantom = os.path.join(folder, "phantom")
    reg = os.path.join(out, method)
    os.makedirs(reg, exist_ok=True)
    # Variants of the harmonic method: "harmonic-affine" starts from the affine map;
    # "harmonic-threshold" the former fold detection, "harmonic-greedy" the former matching,
    # "harmonic-before" both (the issue-7 state before graph cut and spectral matching).
    variants = {"harmonic-affine": ["--initialMap", "affine"],
                "harmonic-threshold": ["--foldDetection", "threshold"],
                "harmonic-greedy": ["--matching", "greedy"],
                "harmonic-before": ["--foldDetection", "threshold", "--matching", "greedy"]}
    options = ["--method", "harmonic"] + variants[method] if method in variants else ["--method", method]
    values, seconds = run(cli, "ColonRegistration", [os.path.join(flat, "supine"), os.path.join(flat, "prone"), reg,
                                                     "--reportTimes"] + options)
    regvtp = os.path.join(reg, "registration.vtp")
    errors = os.path.join(reg, "errors.json")
    run(cli, "ColonEvaluateRegistration", ["--registration", regvtp,
                                           "--truthSupine", os.path.join(phantom, "supine_eval.mrk.json"),
                                           "--truthProne", os.path.join(phantom, "prone_eval.mrk.json"),
                                           "--polypsSupine", os.path.join(phantom, "supine_polyps.mrk.json"),
                                           "--polypsProne", os.path.join(phantom, "prone_polyps.mrk.json"),
                                           "--output", errors])
    ev = json.load(open(errors))
    points = [pt for pt in ev.pop("points", []) if pt["group"] != "polyps"]
    unc = [pt["uncertainty"] for pt in points]
    err = [pt["error3D"] for pt in points]
    result = {"registrationSeconds": round(seconds, 2), "returns": values, "evaluation": ev,
              "roundTripMeanMm": ev["overall"]["roundTrip"]["mean"],
              "uncertaintyPearson": pearson(unc, err), "uncertaintySpearman": spearman(unc, err),
              "points": points}
    regjson = os.path.join(reg, "registration.json")
    if os.path.exists(regjson):
        doc = json.load(open(regjson))
        result["registrationJson"] = doc
        result["flips"] = doc.get("flippedTriangles")
        result["featureSeconds"] = round(sum(seg.get("times", {}).get("features+matching+harmonic", 0.0)
                                             for seg in doc.get("segments", {}).values()), 3)
    return result


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--cli-dir", required=True)
    p.add_argument("--cache", required=True)
    p.add_argument("--seeds", default="1-10")
    p.add_argument("--spacing", default="0.7,0.7,1.0")
    p.add_argument("--methods", default="conformal,centerline,harmonic")
    p.add_argument("--output", default=None)
    p.add_argument("--work", default=None, help="folder for registration outputs (default: CACHE/seed<N>/runs)")
    p.add_argument("--prepare-only", action="store_true")
    p.add_argument("--dump-points", default=None)
    p.add_argument("--keep-volumes", action="store_true")
    p.add_argument("--real-colon", default=None, help="a real colon folder for ColonPhantom --realColon")
    p.add_argument("--deformation", type=float, default=None)
    p.add_argument("--redo-landmarks", action="store_true",
                   help="recompute landmarks and flattening from the cached surfaces (after a landmark change)")
    a = p.parse_args()
    seeds = parse_seeds(a.seeds)
    methods = a.methods.split(",")
    report = {"spacing": a.spacing, "seeds": {}, "methods": methods, "failed": {},
              "realColon": a.real_colon, "deformation": a.deformation}
    for seed in seeds:
        folder = os.path.join(os.path.abspath(a.cache), f"seed{seed}")
        os.makedirs(folder, exist_ok=True)
        try:
            prepare(a.cli_dir, folder, seed, a.spacing, a.keep_volumes, a.real_colon, a.deformation, a.redo_landmarks)
        except RuntimeError as e:
            print(f"seed {seed}: FAILED: {e}", flush=True)
            report["failed"][seed] = str(e)
            continue
        if a.prepare_only:
            continue
        out = os.path.join(a.work, f"seed{seed}") if a.work else os.path.join(folder, "runs")
        report["seeds"][seed] = {}
        for method in methods:
            try:
                r = evaluate(a.cli_dir, folder, method, out)
            except RuntimeError as e:
                print(f"seed {seed} {method}: FAILED: {e}", flush=True)
                report["failed"][f"{seed}/{method}"] = str(e)
                continue
            report["seeds"][seed][method] = r
            ev = r["evaluation"]
            o = ev["overall"]["error3D"]
            segtext = " ".join(f"{x}:{ev['segments'][x]['error3D']['mean']:.2f}" for x in SEGMENTS if x in ev["segments"])
            print(f"seed {seed} {method:10s}: {o['mean']:.2f}/{o['median']:.2f}/{o['p90']:.2f}/{o['max']:.2f} [{segtext}]"
                  f" polyps {ev.get('polyps', {}).get('error3D', {}).get('mean', float('nan')):.2f}"
                  f" trip {r['roundTripMeanMm']:.3f} flips {r.get('flips')} unc r={r['uncertaintyPearson']}"
                  f" t={r['registrationSeconds']} s", flush=True)
    if a.prepare_only:
        return
    agg = {}
    for method in methods:
        pooled, polyps, segs, trips, flips, secs, fsecs, corr, scorr, per_seed = [], [], {s: [] for s in SEGMENTS}, \
            [], [], [], [], [], [], []
        for seed in seeds:
            r = report["seeds"].get(seed, {}).get(method)
            if r is None:
                continue
            ev = r["evaluation"]
            pooled += [pt["error3D"] for pt in r["points"]]
            for pt in r["points"]:
                if pt["group"] in segs:
                    segs[pt["group"]].append(pt["error3D"])
            if "polyps" in ev:
                polyps.append(ev["polyps"]["error3D"]["mean"])
            trips.append(r["roundTripMeanMm"])
            secs.append(r["registrationSeconds"])
            fsecs.append(r.get("featureSeconds", 0.0))
            if r["uncertaintyPearson"] is not None:
                corr.append(r["uncertaintyPearson"])
                scorr.append(r["uncertaintySpearman"])
            flips.append(r.get("flips"))
            per_seed.append({k: ev["overall"]["error3D"][k] for k in ("mean", "median", "p90", "max")})
        agg[method] = {"pooled": stats(pooled),
                       "perSegmentPooled": {s: stats(v) for s, v in segs.items() if v},
                       "perSeed": per_seed,
                       "meanOfSeedMeans": round(statistics.fmean(x["mean"] for x in per_seed), 3) if per_seed else None,
                       "worstSeed": {k: max(x[k] for x in per_seed) for k in ("mean", "median", "p90", "max")} if per_seed else None,
                       "polypMeanOfSeeds": round(statistics.fmean(polyps), 3) if polyps else None,
                       "polypMeanPerSeed": polyps,
                       "flips": flips, "maxRoundTripMeanMm": max(trips) if trips else None,
                       "registrationSeconds": {"mean": round(statistics.fmean(secs), 2), "max": max(secs)} if secs else None,
                       "featuresMatchingHarmonicSeconds": {"mean": round(statistics.fmean(fsecs), 3), "max": max(fsecs)} if fsecs else None,
                       "uncertaintyPearsonMean": round(statistics.fmean(corr), 3) if corr else None,
                       "uncertaintySpearmanMean": round(statistics.fmean(scorr), 3) if scorr else None}
    report["aggregate"] = agg
    if a.dump_points:
        with open(a.dump_points, "w") as f:
            json.dump({seed: {m: r["points"] for m, r in v.items()} for seed, v in report["seeds"].items()}, f)
    for seed in report["seeds"].values():  # keep the JSON readable: drop the raw per-point lists
        for r in seed.values():
            r.pop("points", None)
    text = json.dumps(report, indent=1, sort_keys=True)
    if a.output:
        with open(a.output, "w") as f:
            f.write(text)
    for seed, why in report["failed"].items():
        print(f"seed {seed} failed: {why}")
    for method in methods:
        g = agg[method]
        if not g["perSeed"]:
            continue
        print(f"{method:10s} pooled {g['pooled']} polyps(mean of seeds) {g['polypMeanOfSeeds']} worst seed {g['worstSeed']}")
        print("           per segment " + ", ".join(f"{s}:{v['mean']}/{v['median']}/{v['p90']}/{v['max']}"
                                             for s, v in g["perSegmentPooled"].items()))


if __name__ == "__main__":
    main()
