#!/usr/bin/env python3
"""Evaluates the cached registrations of a registration_seeds.py cache on many more wall points than
ColonPhantom's 200 (issue 20; a benchmark, not a test). A pair's coverage on 200 points is a sample:
+-2 points of coverage at 90% from the sample alone (binomial); on 2000, +-0.7.

ColonPhantom's supine_truth.vtp and prone_truth.vtp are one mesh in two postures (same vertices,
same faces): a point at barycentric coordinates in a face has its true prone position at the same
coordinates of the same face. Points are drawn as ColonPhantom draws its own: stratified along the
colon (MaterialS, over the span of the phantom's evaluation points), area-weighted inside a stratum,
kept 3 mm clear of a polyp's foot (foot radius taken as 0.6 x the diameter its label gives; the
phantom knows the exact foot). Each point's segment is the one its nearest vertex's SegmentId names,
read off the phantom's own evaluation points. The registration is the one the cache holds (RUNS);
ColonEvaluateRegistration gives each point's true error and bound, as for the 200.

    /usr/bin/python3 scripts/dense_evaluation.py --cli-dir DIR --cache CACHE [--runs runs]
        [--seeds 1-8] [--points 2000] [--dense-runs dense]

writes CACHE/DENSE-RUNS/seed<N>/harmonic/{supine,prone}_dense.mrk.json, errors.json and a copy of
registration.json, the layout fit_uncertainty.py reads (--pool NAME=CACHE:DENSE-RUNS).
Needs numpy and VTK's Python module (Debian: python3-numpy, python3-vtk9).
"""
import argparse
import copy
import json
import os
import re
import shutil
import sys

import numpy as np

from registration_seeds import harmonic_run, parse_seeds, run


def read_wall(path):
    import vtk  # here, so that sample_wall is usable (and testable) with numpy alone
    from vtk.util.numpy_support import vtk_to_numpy
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    poly = reader.GetOutput()
    if poly.GetNumberOfPoints() == 0:
        raise SystemExit(f"dense_evaluation.py: error: '{path}' holds no surface")
    faces = vtk_to_numpy(poly.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    return poly, vtk_to_numpy(poly.GetPoints().GetData()).astype(float), faces


def controls(path):
    doc = json.load(open(path))
    return doc, doc["markups"][0]["controlPoints"]


def describe(point):
    return dict(kv.split("=", 1) for kv in point["description"].split() if "=" in kv)


def sample_wall(supine, prone, faces, s, letters, span, polyps, count, seed):
    """count points on a wall given in two postures (supine, prone: vertices x 3 of the same faces):
    stratified along s (per vertex) over span = (first, last), area-weighted (supine areas) inside a
    stratum, farther than r from every polyp (centre, r). letters: per vertex its segment's letter
    or None (not evaluated). Returns (supine, prone) lists of (label, description, position)."""
    face_s = s[faces].mean(axis=1)
    area = 0.5 * np.linalg.norm(np.cross(supine[faces[:, 1]] - supine[faces[:, 0]],
                                         supine[faces[:, 2]] - supine[faces[:, 0]]), axis=1)
    order = np.argsort(face_s, kind="stable")
    sorted_s = face_s[order]
    cumulative = np.concatenate([[0.0], np.cumsum(area[order])])
    rng = np.random.default_rng(seed)
    length = span[1] - span[0]
    out_supine, out_prone = [], []
    for k in range(count):
        lo, hi = span[0] + (k + 0.1) * length / count, span[0] + (k + 0.9) * length / count
        a, b = np.searchsorted(sorted_s, lo), np.searchsorted(sorted_s, hi, side="right")
        if b <= a:  # a stratum narrower than the wall's rings (the tube's are 1 mm): the ring at it
            a = min(a, len(sorted_s) - 1)
            b = np.searchsorted(sorted_s, sorted_s[a], side="right")
        for _ in range(50):
            pick = cumulative[a] + rng.random() * (cumulative[b] - cumulative[a])
            face = faces[order[min(max(np.searchsorted(cumulative, pick, side="right") - 1, a), b - 1)]]
            u, w = rng.random(), rng.random()
            if u + w > 1.0:
                u, w = 1.0 - u, 1.0 - w
            weights = np.array([1.0 - u - w, u, w])
            x = weights @ supine[face]
            if all(np.linalg.norm(x - c) > r for c, r in polyps):
                break
        else:
            continue
        letter = letters[face[np.argmax(weights)]]
        if letter is None:
            continue  # a part of the colon the phantom does not evaluate
        label, text = f"D{k + 1:05d}", f"segment={letter} s={weights @ s[face]:.4f}"
        out_supine.append((label, text, x))
        out_prone.append((label, text, weights @ prone[face]))
    return out_supine, out_prone


def sample(phantom, count, seed):
    """(supine, prone) lists of (label, description, position) of count points on a phantom's true walls."""
    poly, supine, faces = read_wall(os.path.join(phantom, "supine_truth.vtp"))
    _, prone, prone_faces = read_wall(os.path.join(phantom, "prone_truth.vtp"))
    if supine.shape != prone.shape or not np.array_equal(faces, prone_faces):
        raise SystemExit(f"dense_evaluation.py: error: '{phantom}': the supine and prone true walls are not one mesh")
    from vtk.util.numpy_support import vtk_to_numpy
    s = vtk_to_numpy(poly.GetPointData().GetArray("MaterialS")).astype(float)
    segment_id = vtk_to_numpy(poly.GetPointData().GetArray("SegmentId"))
    # Which SegmentId is which letter, and the span of s, from the phantom's own evaluation points.
    letter, span = {}, [np.inf, -np.inf]
    for p in controls(os.path.join(phantom, "supine_eval.mrk.json"))[1]:
        nearest = int(np.argmin(np.linalg.norm(supine - np.asarray(p["position"]), axis=1)))
        d = describe(p)
        letter.setdefault(int(segment_id[nearest]), d["segment"])
        span = [min(span[0], float(d["s"])), max(span[1], float(d["s"]))]
    polyps = [(np.asarray(p["position"]), 0.6 * float(describe(p).get("diameter", 10.0)) + 3.0)
              for p in controls(os.path.join(phantom, "supine_polyps.mrk.json"))[1]]
    return sample_wall(supine, prone, faces, s, [letter.get(int(i)) for i in segment_id], span, polyps, count, seed)


def write_points(template, points, path):
    doc = copy.deepcopy(template)
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
    for seed in parse_seeds(a.seeds):
        phantom = os.path.join(a.cache, f"seed{seed}", "phantom")
        registration = harmonic_run(a.cache, seed, a.runs)
        if registration is None or not os.path.exists(os.path.join(phantom, "supine_truth.vtp")):
            print(f"seed {seed}: no registration or no true wall, skipped", file=sys.stderr)
            continue
        out = os.path.join(a.cache, a.dense_runs, f"seed{seed}", "harmonic")
        os.makedirs(out, exist_ok=True)
        supine, prone = sample(phantom, a.points, seed)
        write_points(controls(os.path.join(phantom, "supine_eval.mrk.json"))[0], supine,
                     os.path.join(out, "supine_dense.mrk.json"))
        write_points(controls(os.path.join(phantom, "prone_eval.mrk.json"))[0], prone,
                     os.path.join(out, "prone_dense.mrk.json"))
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
        print(f"seed {seed}: {len(wall)} points, mean error {np.mean([p['error3D'] for p in wall]):.2f} mm, "
              f"within their bound {covered:.3f}", flush=True)


if __name__ == "__main__":
    main()
