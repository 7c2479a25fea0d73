#!/usr/bin/env python3
"""Evaluates the cached registrations of a registration_seeds.py cache on many more wall points than
ColonPhantom's 200 (issue 20; a benchmark, not a test). A pair's coverage on 200 points is a sample:
+-2 points of coverage at 90% from the sample alone (binomial); on 2000, +-0.7.

ColonPhantom's supine_truth.vtp and prone_truth.vtp are one mesh in two postures (same vertices,
same faces): a point at barycentric coordinates in a face has its true prone position at the same
coordinates of the same face. Points are drawn stratified along the colon (MaterialS, over the span
of the phantom's own evaluation points), area-weighted inside a stratum, kept 3 mm clear of a
polyp's foot (foot radius taken as 0.6 x the diameter its label gives). ColonPhantom draws its 200
so on a real colon; on the tube it draws uniformly in (s, angle) on the analytic tube, which the
tube's even rings make the same to within the mesh. Each point's segment is that of the face's
vertex nearest it (SegmentId: 0..4 = A, T, D, S, R). The registration is the one the cache holds
(RUNS); ColonEvaluateRegistration gives each point's true error and bound, as for the 200. Pairs
with collapsed stretches are refused: the dense points carry no collapsed= tag.

    /usr/bin/python3 scripts/dense_evaluation.py --cli-dir DIR --cache CACHE [--runs runs]
        [--seeds 1-8] [--points 2000] [--dense-runs dense]

writes CACHE/DENSE-RUNS/seed<N>/harmonic/{supine,prone}_dense.mrk.json, errors.json and a copy of
registration.json, the layout fit_uncertainty.py reads (--pool NAME=CACHE:DENSE-RUNS).
Needs numpy and VTK's Python module (Debian: python3-numpy, python3-vtk9).
"""
import argparse
import json
import os
import shutil
import sys

import numpy as np

from registration_seeds import SEGMENTS, harmonic_run, markup_points, parse_seeds, run


def read_wall(path):
    """(vertices, faces, {name: point array}) of a ColonPhantom true wall."""
    # VTK here, so that sample_wall is usable (and testable) with numpy alone.
    from shape_limit import read_surface
    from vtk.util.numpy_support import vtk_to_numpy
    poly = read_surface(path)
    faces = vtk_to_numpy(poly.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    data = poly.GetPointData()
    arrays = {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)) for i in range(data.GetNumberOfArrays())}
    return vtk_to_numpy(poly.GetPoints().GetData()).astype(float), faces, arrays


def describe(text):
    """The key=value fields of a ColonPhantom markup description."""
    return dict(kv.split("=", 1) for kv in text.split() if "=" in kv)


def sample_wall(supine, prone, faces, s, letters, span, polyps, count, seed):
    """count points on a wall given in two postures (supine, prone: vertices x 3 of the same faces):
    stratified along s (per vertex) over span = (first, last), area-weighted (supine areas) inside a
    stratum, farther than r from every polyp (centre, r). letters: per vertex its segment's letter
    or None (not evaluated). Returns (supine, prone) lists of (label, description, position)."""
    face_s = s[faces].mean(axis=1)
    face_lo, face_hi = s[faces].min(axis=1), s[faces].max(axis=1)
    area = 0.5 * np.linalg.norm(np.cross(supine[faces[:, 1]] - supine[faces[:, 0]],
                                         supine[faces[:, 2]] - supine[faces[:, 0]]), axis=1)
    order = np.argsort(face_s, kind="stable")
    sorted_s = face_s[order]
    rng = np.random.default_rng(seed)
    length = span[1] - span[0]
    out_supine, out_prone = [], []
    for k in range(count):
        lo, hi = span[0] + (k + 0.1) * length / count, span[0] + (k + 0.9) * length / count
        a, b = np.searchsorted(sorted_s, lo), np.searchsorted(sorted_s, hi, side="right")
        candidates = order[a:b]
        if b <= a:  # a stratum narrower than the wall's rings (the tube's are 1 mm): the faces across it
            candidates = np.nonzero((face_lo <= hi) & (face_hi >= lo))[0]
        weights_of = np.cumsum(area[candidates])
        for _ in range(50):
            face = faces[candidates[min(np.searchsorted(weights_of, rng.random() * weights_of[-1], side="right"),
                                        len(candidates) - 1)]]
            u, w = rng.random(), rng.random()
            if u + w > 1.0:
                u, w = 1.0 - u, 1.0 - w
            weights = np.array([1.0 - u - w, u, w])
            x = weights @ supine[face]
            if all(np.linalg.norm(x - c) > r for c, r in polyps):
                break
        else:
            continue
        letter = letters[face[np.argmax(weights)]]  # the largest weight: the face's vertex nearest x
        if letter is None:
            continue  # a part of the colon the phantom does not evaluate
        label, text = f"D{k + 1:05d}", f"segment={letter} s={weights @ s[face]:.4f}"
        out_supine.append((label, text, x))
        out_prone.append((label, text, weights @ prone[face]))
    return out_supine, out_prone


def sample(phantom, count, seed):
    """(supine, prone) lists of (label, description, position) of count points on a phantom's true walls."""
    if json.load(open(os.path.join(phantom, "truth.json"))).get("collapses"):
        raise SystemExit(f"dense_evaluation.py: error: '{phantom}' has collapsed stretches, which the dense points do not mark")
    supine, faces, arrays = read_wall(os.path.join(phantom, "supine_truth.vtp"))
    prone, prone_faces, _ = read_wall(os.path.join(phantom, "prone_truth.vtp"))
    if supine.shape != prone.shape or not np.array_equal(faces, prone_faces):
        raise SystemExit(f"dense_evaluation.py: error: '{phantom}': the supine and prone true walls are not one mesh")
    # The span of s, and which segments are evaluated, from the phantom's own evaluation points.
    own = [describe(text) for _, text in markup_points(os.path.join(phantom, "supine_eval.mrk.json")).values()]
    span = (min(float(d["s"]) for d in own), max(float(d["s"]) for d in own))
    evaluated = {d["segment"] for d in own}
    letters = [SEGMENTS[i] if 0 <= i < len(SEGMENTS) and SEGMENTS[i] in evaluated else None
               for i in arrays["SegmentId"].astype(int)]
    polyps = [(np.asarray(x), 0.6 * float(describe(text).get("diameter", 10.0)) + 3.0)
              for x, text in markup_points(os.path.join(phantom, "supine_polyps.mrk.json")).values()]
    return sample_wall(supine, prone, faces, arrays["MaterialS"].astype(float), letters, span, polyps, count, seed)


def write_points(template, points, path):
    """points as a markups file shaped like the file template (its first control point's fields)."""
    doc = json.load(open(template))
    first = doc["markups"][0]["controlPoints"][0]
    doc["markups"][0]["controlPoints"] = [dict(first, id=str(i + 1), label=label, description=text,
                                               position=[float(c) for c in x])
                                          for i, (label, text, x) in enumerate(points)]
    json.dump(doc, open(path, "w"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cli-dir", required=True, help="folder of the ColonMap CLI modules")
    ap.add_argument("--cache", required=True, help="registration_seeds.py cache (CACHE/seed<N>/phantom)")
    ap.add_argument("--runs", default="runs", help="where the cache's registrations lie (as fit_uncertainty.py's RUNS)")
    ap.add_argument("--seeds", default="1-8")
    ap.add_argument("--points", type=int, default=2000)
    ap.add_argument("--dense-runs", default="dense", help="output: CACHE/DENSE-RUNS/seed<N>/harmonic")
    a = ap.parse_args()
    if not os.path.isdir(a.cache):
        raise SystemExit(f"dense_evaluation.py: error: cache '{a.cache}' is not a folder")
    evaluated = 0
    for seed in parse_seeds(a.seeds):
        phantom = os.path.join(a.cache, f"seed{seed}", "phantom")
        registration = harmonic_run(a.cache, seed, a.runs)
        if registration is None or not os.path.exists(os.path.join(phantom, "supine_truth.vtp")):
            print(f"seed {seed}: no registration or no true wall, skipped", file=sys.stderr)
            continue
        out = os.path.join(a.cache, a.dense_runs, f"seed{seed}", "harmonic")
        os.makedirs(out, exist_ok=True)
        supine, prone = sample(phantom, a.points, seed)
        for posture, points in (("supine", supine), ("prone", prone)):
            write_points(os.path.join(phantom, f"{posture}_eval.mrk.json"), points,
                         os.path.join(out, f"{posture}_dense.mrk.json"))
        shutil.copy(os.path.join(registration, "registration.json"), out)
        run(a.cli_dir, "ColonEvaluateRegistration",
            ["--registration", os.path.join(registration, "registration.vtp"),
             "--truthSupine", os.path.join(out, "supine_dense.mrk.json"),
             "--truthProne", os.path.join(out, "prone_dense.mrk.json"),
             "--polypsSupine", os.path.join(phantom, "supine_polyps.mrk.json"),
             "--polypsProne", os.path.join(phantom, "prone_polyps.mrk.json"),
             "--output", os.path.join(out, "errors.json")])
        errors = json.load(open(os.path.join(out, "errors.json")))
        wall = [p for p in errors["points"] if p["group"] != "polyps"]
        covered = sum(p["error3D"] <= p["uncertainty"] for p in wall) / max(1, len(wall))
        evaluated += 1
        print(f"seed {seed}: {len(wall)} points, mean error {np.mean([p['error3D'] for p in wall]):.2f} mm, "
              f"within their bound {covered:.3f}", flush=True)
    if not evaluated:
        raise SystemExit(f"dense_evaluation.py: error: no pair of '{a.cache}' (seeds {a.seeds}) has a registration "
                         f"under '{a.runs}' and true walls")


if __name__ == "__main__":
    main()
