#!/usr/bin/env python3
"""ColonRegistration as a user runs it, checked against the phantom's exact correspondence: the
test data are the phantom's TRUE walls, where supine vertex i and prone vertex i of a segment are
the same tissue (equal MaterialS/MaterialTheta), so the true prone position of every supine vertex
is known. Checks outputs and arrays, zero flips, triangle ids in range, the measured vertex error
(printed per segment; the conformal baseline vs the centerline arc-length baseline), the inverse
(prone -> supine) is the inverse of the same map, determinism, and errors (missing folder,
mismatched segments).

Usage: colon_registration_test.py <ColonRegistration> <registration data folder>
"""
import filecmp
import json
import os
import shutil
import subprocess
import sys
import tempfile

import math
import statistics

import vtk

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

exe, data = sys.argv[1], sys.argv[2]
checks = Checks()
check = checks.check
NAMES = ["A", "T", "D", "S", "R"]


def run(*args):
    return run_program(exe, *args)


def tuples(a):
    n, k = a.GetNumberOfTuples(), a.GetNumberOfComponents()
    if k == 1:
        return [a.GetValue(i) for i in range(n)]
    return [a.GetTuple(i) for i in range(n)]


def read(path):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    pd = r.GetOutput()
    pts = [pd.GetPoint(i) for i in range(pd.GetNumberOfPoints())]
    conn = pd.GetPolys().GetConnectivityArray()
    c = [conn.GetValue(i) for i in range(conn.GetNumberOfTuples())]
    faces = [tuple(c[3 * i:3 * i + 3]) for i in range(len(c) // 3)]
    arrays = {pd.GetPointData().GetArrayName(i): tuples(pd.GetPointData().GetArray(i))
              for i in range(pd.GetPointData().GetNumberOfArrays())}
    cells = {pd.GetCellData().GetArrayName(i): tuples(pd.GetCellData().GetArray(i))
             for i in range(pd.GetCellData().GetNumberOfArrays())}
    return pts, faces, arrays, cells


def dist(a, b):
    return math.dist(a, b)


def combo(b, corners):
    return tuple(sum(b[k] * corners[k][d] for k in range(3)) for d in range(3))


def pct(values, q):
    v = sorted(values)
    x = q * (len(v) - 1)
    i = int(x)
    j = min(i + 1, len(v) - 1)
    return v[i] + (x - i) * (v[j] - v[i])


def stats(v):
    return sum(v) / len(v), pct(v, 0.5), pct(v, 0.9), max(v)


def vertex_errors(out):
    """Distance from each supine vertex's image to its true prone position, per segment."""
    sp, sf, sa, sc = read(os.path.join(out, "registration.vtp"))
    pp, pf, pa, pc = read(os.path.join(out, "registration_prone.vtp"))
    errors = {}
    for k, x in enumerate(NAMES):
        s = [i for i, v in enumerate(sa["SegmentId"]) if v == k]
        p = [i for i, v in enumerate(pa["SegmentId"]) if v == k]
        if not check(len(s) == len(p) and len(s) > 0, f"segment {x}: vertex counts"):
            continue
        same = all(abs(sa["MaterialS"][i] - pa["MaterialS"][j]) < 1e-6 and abs(sa["MaterialTheta"][i] - pa["MaterialTheta"][j]) < 1e-6
                   for i, j in zip(s, p))
        check(same, f"segment {x}: supine and prone vertices are not the same tissue (test data assumption)")
        errors[x] = [dist(sa["PronePosition"][i], pp[j]) for i, j in zip(s, p)]
    return sp, sf, sa, sc, pp, pf, pa, pc, errors


work = tempfile.mkdtemp(prefix="colonmap-registration-test-")
try:
    out = os.path.join(work, "reg")
    ret = os.path.join(work, "ret.txt")
    r = run("--returnparameterfile", ret, "--method", "conformal", os.path.join(data, "supine"),
            os.path.join(data, "prone"), out)
    check(r.returncode == 0 and r.stderr == "", f"run: {r.returncode} {r.stderr}")
    # The conformal baseline matches no folds: a segment whose curvature images do not agree either
    # is reported as untrusted (issue 20); no other warning.
    other = [l for l in r.stdout.splitlines() if "WARNING" in l and "cannot be trusted" not in l]
    check("<filter-end>" in r.stdout and not other, f"progress or warnings: {other or r.stdout[-500:]}")
    print("conformal: untrusted segments '" + return_parameters(ret).get("untrustedSegments", "?") + "'")
    for name in ("registration.vtp", "registration_prone.vtp", "registration.json"):
        check(os.path.isfile(os.path.join(out, name)), f"{name} missing")
    rets = dict(l.split(" = ", 1) for l in open(ret).read().splitlines())
    check(rets.get("segments") == "5" and rets.get("flippedTriangles") == "0", f"returns {rets}")
    report = json.load(open(os.path.join(out, "registration.json")))
    check(report["flippedTriangles"] == 0, "flips")
    for x in NAMES:
        s = report["segments"][x]
        check(s["flatFlips"] == 0 and s["surfaceFlips"] == 0, f"{x}: flips {s['flatFlips']} {s['surfaceFlips']}")
        check(s["shift"] == 0.0 and s["shiftFromCorrelation"] is False, f"{x}: same cut TO must give shift 0")
        # Reported, not asserted: on the smooth true-wall phantom the curvature images correlate
        # weakly (~0.1), so the correlation's shift is not reliable here.
        print(f"{x}: curvature correlation shift {s['correlationShift']:+.4f} (corr {s['correlation']['atShift']:.3f}, at 0: {s['correlation']['atZero']:.3f})")
        check(s["scale"] > 0, f"{x}: scale")
    sp, sf, sa, sc, pp, pf, pa, pc, errors = vertex_errors(out)
    for a in ("SegmentId", "SupineFlatUV", "ProneFlatUV", "ProneTriangleId", "ProneBarycentric", "PronePosition"):
        check(a in sa, f"registration.vtp: no {a}")
    for a in ("SupineTriangleId", "SupineBarycentric", "SupinePosition", "SupineFlatUV", "ProneFlatUV"):
        check(a in pa, f"registration_prone.vtp: no {a}")
    for a in ("BeltramiAbs", "BeltramiArg", "Dilatation"):
        check(a in sc and len(sc[a]) == len(sf), f"registration.vtp: cell data {a}")
    check(min(sa["ProneTriangleId"]) >= 0 and max(sa["ProneTriangleId"]) < len(pf), "ProneTriangleId range")
    check(min(pa["SupineTriangleId"]) >= 0 and max(pa["SupineTriangleId"]) < len(sf), "SupineTriangleId range")
    b = sa["ProneBarycentric"]
    check(all(abs(sum(t) - 1) < 1e-9 and min(t) >= 0 for t in b), "barycentric coordinates")
    # PronePosition is the barycentric combination of the prone triangle's corners.
    dev = max(dist(combo(b[i], [pp[v] for v in pf[f]]), sa["PronePosition"][i]) for i, f in enumerate(sa["ProneTriangleId"]))
    check(dev < 1e-4, f"PronePosition = bary combination ({dev})")
    check(max(sc["BeltramiAbs"]) < 1 and all(math.isfinite(k) for k in sc["Dilatation"]), "|mu| < 1 everywhere")
    # Round trip through the stored maps: supine vertex -> prone image -> back through the images
    # of the prone triangle's corners (SupinePosition, the inverse map), mean distance <= 1 mm.
    rt = [dist(combo(b[i], [pa["SupinePosition"][v] for v in pf[f]]), sp[i]) for i, f in enumerate(sa["ProneTriangleId"])]
    print(f"round trip supine -> prone -> supine at the vertices: mean {sum(rt) / len(rt):.3f} mm, max {max(rt):.3f} mm")
    check(sum(rt) / len(rt) <= 1.0, f"round trip mean {sum(rt) / len(rt)}")

    # The centerline arc-length baseline on the same data, for the table.
    outc = os.path.join(work, "centerline")
    r = run("--method", "centerline", os.path.join(data, "supine"), os.path.join(data, "prone"), outc)
    check(r.returncode == 0 and r.stderr == "", f"centerline run: {r.stderr}")
    errors_c = vertex_errors(outc)[-1]
    print("vertex error (mm), supine vertex image vs its true prone position")
    print("segment  conformal mean/median/p90/max   centerline mean/median/p90/max")
    allc, allk = [], []
    for x in NAMES:
        e, c = errors[x], errors_c[x]
        allc += e
        allk += c
        print(f"{x:7s}  " + " ".join(f"{v:6.2f}" for v in stats(e)) + "     " + " ".join(f"{v:6.2f}" for v in stats(c)))
    print("all      " + " ".join(f"{v:6.2f}" for v in stats(allc)) + "     " + " ".join(f"{v:6.2f}" for v in stats(allk)))
    # A broken map (a wrong shift, a reversed v) gives errors of tens of mm: a loose sanity bound,
    # not a target (the targets are for the full method, not this baseline).
    check(stats(allc)[0] < 15.0, f"conformal baseline vertex error mean {stats(allc)[0]}")

    # The harmonic method (matched folds + harmonic correction) on the same data: one-to-one,
    # matched features written as markups with the same labels in both scans, and (the measured
    # claim) a lower mean vertex error than the conformal map it corrects.
    outh = os.path.join(work, "harmonic")
    r = run("--method", "harmonic", os.path.join(data, "supine"), os.path.join(data, "prone"), outh)
    check(r.returncode == 0 and r.stderr == "" and "WARNING" not in r.stdout, f"harmonic run: {r.stderr} {r.stdout[-300:]}")
    errors_h = vertex_errors(outh)[-1]
    hreport = json.load(open(os.path.join(outh, "registration.json")))
    check(hreport["flippedTriangles"] == 0, "harmonic: flips")
    matched = 0
    for x in NAMES:
        f = hreport["segments"][x]["features"]
        matched += f["matched"]
        print(f"{x}: folds {f['supine']}/{f['prone']}, matched {f['matched']} (guard dropped {f['droppedByGuard']}), h scale {f['hScale']}")
    sf = json.load(open(os.path.join(outh, "supine_features.mrk.json")))
    pfm = json.load(open(os.path.join(outh, "prone_features.mrk.json")))
    sl = [c["label"] for c in sf["markups"][0]["controlPoints"]]
    pl = [c["label"] for c in pfm["markups"][0]["controlPoints"]]
    check(len(sl) == matched and sl == pl and all(l.startswith("F") for l in sl), f"feature markups {len(sl)} {len(pl)} {matched}")
    allh = [e for x in NAMES for e in errors_h[x]]
    print("harmonic  " + " ".join(f"{v:6.2f}" for v in stats(allh)) + "   (per segment: " +
          ", ".join(f"{x} {stats(errors_h[x])[0]:.2f}" for x in NAMES) + ")")
    check(stats(allh)[0] < stats(allc)[0], f"harmonic mean {stats(allh)[0]} not below conformal {stats(allc)[0]}")

    # Trust (issue 20): each segment says whether it is trusted and its expected error; Reliable is
    # 0/1 per vertex and 1 on trusted segments away from suspect flexures.
    _, _, harrays, _ = read(os.path.join(outh, "registration.vtp"))
    for x in NAMES:
        seg = hreport["segments"][x]
        check(isinstance(seg.get("trusted"), bool) and seg.get("expectedErrorMm", 0) > 0, f"{x}: trust fields {seg.get('trusted')}")
        check("curvatureAgreement" in seg["uncertainty"] and "lengthMismatch" in seg["uncertainty"], f"{x}: evidence fields")
        # The pair is deformed, so no segment moved rigidly (RigidResidual.h has the known answers).
        check(seg["uncertainty"].get("deformationMm", 0) > 0, f"{x}: deformationMm {seg['uncertainty'].get('deformationMm')}")
    check(set(harrays["Reliable"]) <= {0.0, 1.0}, "Reliable is 0/1")
    check(all(r == (t == 1.0 and u <= hreport["reliableBoundMm"]) for r, t, u in
              zip(harrays["Reliable"], harrays["Trusted"], harrays["Uncertainty90"])), "Reliable = Trusted and bound <= reliableBoundMm")
    check(all(v >= 0 for v in harrays["UncertaintyFlexureMm"]), "UncertaintyFlexureMm")
    print("trusted segments: " + " ".join(f"{x}:{hreport['segments'][x]['trusted']}" for x in NAMES) +
          f", trusted vertices {sum(harrays['Trusted']) / len(harrays['Trusted']):.2f}"
          f", reliable vertices {sum(harrays['Reliable']) / len(harrays['Reliable']):.2f}")
    # Flexures found for each scan alone (ColonLandmarks without --pairedSurface records it, and
    # flattening.json hands it on): nothing can be trusted, every vertex is unreliable, a warning.
    alone = os.path.join(work, "supine-alone")
    shutil.copytree(os.path.join(data, "supine"), alone)
    fj = os.path.join(alone, "flattening.json")
    rep = json.load(open(fj)) if os.path.exists(fj) else {}
    rep["jointChoice"] = {"pairedWith": "", "consistent": True, "fallback": False}
    json.dump(rep, open(fj, "w"))
    outa = os.path.join(work, "alone")
    rp = os.path.join(work, "alone-returns.txt")
    r = run("--returnparameterfile", rp, "--method", "harmonic", alone, os.path.join(data, "prone"), outa)
    ret = return_parameters(rp)
    check(r.returncode == 0 and ret.get("untrustedSegments") == "A,T,D,S,R", f"alone: {ret.get('untrustedSegments')} {r.stderr}")
    check("flexures not chosen jointly" in r.stdout and "WARNING" in r.stdout, "alone: warning")
    _, _, aarrays, _ = read(os.path.join(outa, "registration.vtp"))
    check(max(aarrays["Reliable"]) == 0.0 and max(aarrays["Trusted"]) == 0.0, "alone: every vertex unreliable")
    # A bad bound option is refused before anything is written.
    r = run("--reliableBoundMm", "nan", os.path.join(data, "supine"), os.path.join(data, "prone"), os.path.join(work, "nanbound"))
    check(r.returncode != 0 and "reliableBoundMm" in r.stderr and not os.path.exists(os.path.join(work, "nanbound")),
          f"nan bound: {r.stderr}")

    # Determinism: a second run gives identical files.
    out2 = os.path.join(work, "reg2")
    run("--method", "conformal", os.path.join(data, "supine"), os.path.join(data, "prone"), out2)
    for name in ("registration.vtp", "registration_prone.vtp", "registration.json"):
        check(filecmp.cmp(os.path.join(out, name), os.path.join(out2, name), shallow=False), f"{name} differs between runs")

    # Errors: missing folder; mismatched segments. Nothing is left behind.
    bad = os.path.join(work, "bad")
    r = run(os.path.join(work, "nope"), os.path.join(data, "prone"), bad)
    check(r.returncode != 0 and "does not exist" in r.stderr and len(r.stderr.strip().splitlines()) == 1, f"missing: {r.stderr}")
    check(not os.path.exists(bad), "output left after an error")
    partial = os.path.join(work, "prone-partial")
    shutil.copytree(os.path.join(data, "prone"), partial)
    os.remove(os.path.join(partial, "flat_T.vtp"))
    r = run(os.path.join(data, "supine"), partial, bad)
    check(r.returncode != 0 and "mismatched segments" in r.stderr and "flat_T.vtp" in r.stderr, f"mismatch: {r.stderr}")
    check(not os.path.exists(bad), "output left after the mismatch error")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
