#!/usr/bin/env python3
"""How far a segment's wall can be registered from its 3D shape alone (issue 19; a benchmark, not a
test). For each pair of a registration_seeds.py cache, on one segment (our own flattening's
supine and prone cut surfaces, flattening/<scan>/surface_<S>.vtp) and its evaluation points:

  registration: the mean true error of ColonRegistration there (CACHE/seed<N>/RUNS/harmonic/errors.json);
  none:         the distance from each supine point to its true prone partner;
  rigid:        rigid ICP of the supine surface onto the prone one (VTK), then the closest prone point;
  nonrigid:     after the rigid ICP, a smooth non-rigid ICP: closest-point displacements of 800
                control vertices, spread by Gaussian weights (sigma 30 mm, then 15 mm, 8 rounds each),
                then the closest prone point; and the mean gap left between the two surfaces;
  arc:          the registration's image moved along the colon, around kept: of the prone vertices
                of the segment within 0.03 flat widths of the image's u, the one whose
                CenterlineArcLength is nearest the supine vertex's, mapped by the segment's affine
                arc map (1st to 99th percentile of each scan's arc lengths).

Where the non-rigid alignment leaves the surfaces within about a millimetre of each other and the
points still far from their partners, the wall slid over a shape that did not change: no method
that reads the shape can see that slide (docs/accuracy.md, the HuBMAP VHF sigmoid).

    /usr/bin/python3 scripts/shape_limit.py --cache CACHE [--runs runs] [--segment S] [--seeds 1-8] [--output F.json]

Needs numpy and VTK's Python module (Debian: python3-numpy, python3-vtk9).
"""
import argparse
import json
import os

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

from registration_seeds import harmonic_run, markup_points, parse_seeds


def read_surface(path):
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetOutput().GetNumberOfPoints() == 0:
        raise SystemExit(f"shape_limit.py: error: '{path}' is missing or empty")
    return reader.GetOutput()


def markup_positions(path):
    return {label: np.array(position, float) for label, (position, _) in markup_points(path).items()}


def closest_points(locator, points):
    out = np.zeros_like(points)
    c, cell, sub, d2 = [0.0] * 3, vtk.reference(0), vtk.reference(0), vtk.reference(0.0)
    for i, x in enumerate(points):
        locator.FindClosestPoint(x, c, cell, sub, d2)
        out[i] = c
    return out


def rigid_icp(source, target):
    icp = vtk.vtkIterativeClosestPointTransform()
    icp.SetSource(source)
    icp.SetTarget(target)
    icp.GetLandmarkTransform().SetModeToRigidBody()
    icp.SetMaximumNumberOfIterations(200)
    icp.SetMaximumNumberOfLandmarks(5000)
    icp.StartByMatchingCentroidsOn()
    icp.Update()
    return lambda points: np.array([icp.TransformPoint(x) for x in points])


def gaussian_spread(at, control, displacement, sigma):
    """Displacement at each row of `at`: the Gaussian-weighted mean of the control displacements."""
    w = np.exp(-((at[:, None, :] - control[None, :, :]) ** 2).sum(-1) / (2.0 * sigma * sigma))
    return (w @ displacement) / np.maximum(w.sum(1, keepdims=True), 1e-12)


def point_array(poly, name):
    return vtk_to_numpy(poly.GetPointData().GetArray(name))


def arc_moved(run, segment, points):
    """The registration's images of the supine points (nearest supine vertex), moved along the colon
    to the prone vertex of the same u whose arc length the affine arc map gives."""
    s = read_surface(os.path.join(run, "registration.vtp"))
    p = read_surface(os.path.join(run, "registration_prone.vtp"))
    k = "ATDSR".index(segment)
    s_in, p_in = point_array(s, "SegmentId").astype(int) == k, point_array(p, "SegmentId").astype(int) == k
    s_arc, p_arc = point_array(s, "CenterlineArcLength"), point_array(p, "CenterlineArcLength")
    a0, a1 = np.percentile(s_arc[s_in], [1, 99])
    b0, b1 = np.percentile(p_arc[p_in], [1, 99])
    image_uv, prone_uv = point_array(s, "ProneFlatUV"), point_array(p, "ProneFlatUV")
    prone_xyz = vtk_to_numpy(p.GetPoints().GetData())
    ids = np.where(p_in)[0]
    locator = vtk.vtkStaticPointLocator()
    locator.SetDataSet(s)
    locator.BuildLocator()
    out = np.zeros_like(points)
    for n, x in enumerate(points):
        i = locator.FindClosestPoint(x)
        target = b0 + (s_arc[i] - a0) * (b1 - b0) / (a1 - a0)
        near_u = np.abs((prone_uv[ids, 0] - image_uv[i, 0] + 0.5) % 1.0 - 0.5) < 0.03
        candidates = ids[near_u] if near_u.any() else ids
        out[n] = prone_xyz[candidates[np.argmin(np.abs(p_arc[candidates] - target))]]
    return out


def one_pair(folder, run, segment):
    supine = read_surface(os.path.join(folder, "flattening", "supine", f"surface_{segment}.vtp"))
    prone = read_surface(os.path.join(folder, "flattening", "prone", f"surface_{segment}.vtp"))
    errors = json.load(open(os.path.join(run, "errors.json")))["points"]
    labels = [p["label"] for p in errors if p["group"] == segment]
    if not labels:
        return None
    registered = np.array([p["error3D"] for p in errors if p["group"] == segment])
    s = markup_positions(os.path.join(folder, "phantom", "supine_eval.mrk.json"))
    t = markup_positions(os.path.join(folder, "phantom", "prone_eval.mrk.json"))
    points, truth = np.array([s[k] for k in labels]), np.array([t[k] for k in labels])
    locator = vtk.vtkCellLocator()
    locator.SetDataSet(prone)
    locator.BuildLocator()
    transform = rigid_icp(supine, prone)
    moved = transform(vtk_to_numpy(supine.GetPoints().GetData()).astype(float))
    mapped = transform(points)
    rigid = np.linalg.norm(closest_points(locator, mapped) - truth, axis=1)
    control = np.random.default_rng(0).choice(len(moved), min(800, len(moved)), replace=False)
    for sigma in (30.0, 15.0):
        for _ in range(8):
            d = closest_points(locator, moved[control]) - moved[control]
            mapped = mapped + gaussian_spread(mapped, moved[control], d, sigma)
            moved = moved + gaussian_spread(moved, moved[control], d, sigma)
    nonrigid = np.linalg.norm(closest_points(locator, mapped) - truth, axis=1)
    gap = np.linalg.norm(closest_points(locator, moved[control]) - moved[control], axis=1)
    arc = np.linalg.norm(arc_moved(run, segment, points) - truth, axis=1)
    stats = lambda e: {"mean": round(float(e.mean()), 2), "p90": round(float(np.percentile(e, 90)), 2)}
    return {"points": len(labels), "registration": stats(registered),
            "none": stats(np.linalg.norm(points - truth, axis=1)), "rigid": stats(rigid), "nonrigid": stats(nonrigid),
            "nonrigidSurfaceGapMm": round(float(gap.mean()), 2), "arc": stats(arc)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cache", required=True, help="a registration_seeds.py cache (CACHE/seed<N>)")
    ap.add_argument("--runs", default="runs", help="the registration runs' folder: CACHE/seed<N>/RUNS or CACHE/RUNS/seed<N>")
    ap.add_argument("--segment", default="S", choices=list("ATDSR"))
    ap.add_argument("--seeds", default="1-8", help="e.g. 1-8 or 1,3,5")
    ap.add_argument("--output", default=None)
    a = ap.parse_args()
    out = {"cache": a.cache, "segment": a.segment, "pairs": {}}
    for seed in parse_seeds(a.seeds):
        run = harmonic_run(a.cache, seed, a.runs)
        r = one_pair(os.path.join(a.cache, f"seed{seed}"), run, a.segment) if run else None
        if r is None:
            continue
        out["pairs"][seed] = r
        print(f"seed {seed} {a.segment}: registration {r['registration']['mean']:.2f} mm, none {r['none']['mean']:.2f}, "
              f"rigid ICP {r['rigid']['mean']:.2f}, non-rigid ICP {r['nonrigid']['mean']:.2f} "
              f"(surfaces {r['nonrigidSurfaceGapMm']:.2f} mm apart), along by arc {r['arc']['mean']:.2f} "
              f"(p90 {r['arc']['p90']:.1f})", flush=True)
    pairs = out["pairs"].values()
    for k in ("registration", "none", "rigid", "nonrigid", "arc"):
        out[k + "MeanOfPairs"] = round(float(np.mean([p[k]["mean"] for p in pairs])), 2) if pairs else None
    if a.output:
        json.dump(out, open(a.output, "w"), indent=1)


if __name__ == "__main__":
    main()
