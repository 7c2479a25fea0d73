#!/usr/bin/env python3
"""ColonFlatViews as a user runs it, on the registration test data (the phantom's true walls,
flattened by ColonFlattening and registered by ColonRegistration) and on a harmonic registration
of the same data made here. Checks: every output present; picture sizes follow the flat
rectangles (pixels per unit x flat width/length, read from registration.vtp); distortion.vtp
carries the registration's K, theta = arg(mu)/2, the prone geometry and 0/1 textures; the morph
frames run from the supine to the prone positions; flatviews.json's K statistics agree with the
registration's; the measured claim: the prone curvature picture resampled through the
registration correlates better with the supine picture than the unregistered one (numbers
printed); matched features from a harmonic registration; determinism; bad input (missing
registration.vtp: one stderr line, non-zero exit, no output).

Usage: colon_flat_views_test.py <ColonFlatViews> <ColonRegistration> <registration data folder>
"""
import filecmp
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile

import vtk

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

exe, register, data = sys.argv[1], sys.argv[2], sys.argv[3]
checks = Checks()
check = checks.check
NAMES = ["A", "T", "D", "S", "R"]
PICTURES = ["flat_pair_unregistered.png", "flat_pair_registered.png", "features_matched.png", "dilatation_flat.png",
            "angle_flat.png", "checkerboard_pair.png", "circles_pair.png"]


def read(path):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def values(a):
    n, k = a.GetNumberOfTuples(), a.GetNumberOfComponents()
    return [a.GetValue(i) for i in range(n)] if k == 1 else [a.GetTuple(i) for i in range(n)]


def arr(pd, name, cells=False):
    a = (pd.GetCellData() if cells else pd.GetPointData()).GetArray(name)
    return None if a is None else values(a)


def points(pd):
    return [pd.GetPoint(i) for i in range(pd.GetNumberOfPoints())]


def maxdiff(a, b):
    return max(abs(x - y) for p, q in zip(a, b) for x, y in zip(p, q))


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    return struct.unpack(">II", head[16:24])


def views(reg, out, *extra):
    return run_program(exe, *extra, os.path.join(data, "supine"), os.path.join(data, "prone"), reg, out)


work = tempfile.mkdtemp(prefix="colonmap-flatviews-test-")
try:
    reg = os.path.join(data, "registration")
    out = os.path.join(work, "views")
    ret = os.path.join(work, "ret.txt")
    ppu, frames = 64, 4
    r = views(reg, out, "--returnparameterfile", ret, "--pixelsPerUnit", str(ppu), "--morphFrames", str(frames))
    check(r.returncode == 0 and r.stderr == "", f"run: {r.returncode} {r.stderr}")
    check("<filter-end>" in r.stdout, "progress tags")
    for name in PICTURES + ["distortion.vtp", "flatviews.json"] + [f"morph/morph_{k:03d}.vtp" for k in range(frames)]:
        check(os.path.isfile(os.path.join(out, name)), f"{name} missing")
    check(not os.path.exists(os.path.join(out, f"morph/morph_{frames:03d}.vtp")), "one morph frame too many")
    rets = return_parameters(ret)
    check(rets.get("segments") == "5", f"returns {rets}")
    report = json.load(open(os.path.join(out, "flatviews.json")))

    # Picture sizes: the flat rectangle (width from flattening.json, length = largest v of the
    # segment in registration.vtp) at ppu pixels per unit; the PNG files have the sizes reported.
    sup = read(os.path.join(reg, "registration.vtp"))
    pro = read(os.path.join(reg, "registration_prone.vtp"))
    flat = {s: json.load(open(os.path.join(data, s, "flattening.json"))) for s in ("supine", "prone")}
    for scan, pd, uvname in (("supine", sup, "SupineFlatUV"), ("prone", pro, "ProneFlatUV")):
        seg, uv = arr(pd, "SegmentId"), arr(pd, uvname)
        for k, x in enumerate(NAMES):
            w = flat[scan]["segments"][x]["flatWidth"]
            h = max(uv[i][1] for i in range(len(seg)) if seg[i] == k)
            want = [max(1, round(w * ppu)), max(1, round(h * ppu))]
            got = report["segments"][x][f"{scan}Picture"]
            check(got == want, f"{scan} {x}: picture {got}, flat rectangle gives {want}")
    for name in PICTURES:
        size = png_size(os.path.join(out, name))
        check(size is not None and list(size) == report["pictures"][name], f"{name}: PNG {size} vs report {report['pictures'].get(name)}")
    # The pair pictures stack all segments: taller than the sum of the supine segment heights.
    total = sum(report["segments"][x]["supinePicture"][1] for x in NAMES)
    check(report["pictures"]["flat_pair_registered.png"][1] > total, "registered pair: not all segments stacked")
    check(report["pictures"]["flat_pair_registered.png"][0] > 2 * ppu, "registered pair: not side by side")

    # 3D pictures (the test runs with an X display): present, PNG sizes as reported, one frame
    # per morph step, the anterior camera (looking along +P, superior up) framing the surfaces.
    v3 = report.get("views3D", {})
    check(v3.get("rendered") is True, f"3D pictures not rendered: {v3.get('reason')}")
    names3d = ["distortion_3d.png", "textures_3d.png"] + [f"morph/morph_{k:03d}.png" for k in range(frames)]
    for name in names3d:
        size = png_size(os.path.join(out, name))
        check(size is not None and list(size) == v3.get("pictures", {}).get(name), f"{name}: PNG {size} vs report {v3.get('pictures', {}).get(name)}")
        check(name in report["files"], f"{name} not listed in flatviews.json files")
    check(not os.path.exists(os.path.join(out, f"morph/morph_{frames:03d}.png")), "one morph picture too many")
    rw, rh = v3["renderSize"]
    d3 = v3["pictures"]["distortion_3d.png"]
    check(d3[0] > 2 * rw and d3[1] > rh, f"distortion_3d.png {d3}: not two views of {rw}x{rh} side by side")
    t3 = v3["pictures"]["textures_3d.png"]
    check(t3[0] > 2 * rw and t3[1] > 2 * rh, f"textures_3d.png {t3}: not 2 x 2 views")
    check(len({tuple(v3["pictures"][f"morph/morph_{k:03d}.png"]) for k in range(frames)}) == 1, "morph pictures differ in size")
    cam = v3["camera"]
    look = [f - p for f, p in zip(cam["focalPoint"], cam["position"])]
    check(v3["view"] == "anterior" and look[1] > 0 and abs(look[0]) < 1e-9 and abs(look[2]) < 1e-9 and cam["viewUp"] == [0.0, 0.0, 1.0],
          f"3D camera is not the anterior one: {cam}")
    # The camera frames every vertex of both surfaces: the parallel scale covers the height (z)
    # and width (x) extents of supine and prone points, and not by much more than the larger.
    allp = points(sup) + points(pro)
    half_h = (max(p[2] for p in allp) - min(p[2] for p in allp)) / 2
    half_w = (max(p[0] for p in allp) - min(p[0] for p in allp)) / 2
    need = max(half_h, half_w * rh / rw)
    check(need <= cam["parallelScale"] <= 1.1 * need, f"parallel scale {cam['parallelScale']} for half extent {need}")

    # distortion.vtp: the registration's K, theta = arg(mu)/2, prone geometry, 0/1 textures.
    d = read(os.path.join(out, "distortion.vtp"))
    check(d.GetNumberOfPoints() == sup.GetNumberOfPoints() and d.GetNumberOfCells() == sup.GetNumberOfCells(), "distortion.vtp size")
    K, Kd = arr(sup, "Dilatation", True), arr(d, "Dilatation", True)
    check(Kd is not None and max(abs(a - b) for a, b in zip(K, Kd)) < 1e-9, "distortion.vtp: Dilatation differs from the registration's")
    th, arg = arr(d, "Angle", True), arr(sup, "BeltramiArg", True)
    check(th is not None and max(abs(a - b / 2) for a, b in zip(th, arg)) < 1e-9, "distortion.vtp: Angle is not arg(mu)/2")
    pts = points(d)
    pp, disp = arr(sup, "PronePosition"), arr(d, "ProneDisplacement")
    check(disp is not None and maxdiff([tuple(x + y for x, y in zip(p, q)) for p, q in zip(pts, disp)], pp) < 1e-4, "distortion.vtp: points + ProneDisplacement != PronePosition")
    for t in ("Checkerboard", "Circles"):
        a = arr(d, t)
        check(a is not None and set(a) == {0, 1}, f"distortion.vtp: {t} not 0/1")
    # About half the wall is black on a checkerboard (cells are squares in flat units).
    c = arr(d, "Checkerboard")
    check(0.35 < sum(c) / len(c) < 0.65, f"checkerboard fraction {sum(c) / len(c)}")

    # Morph: frame 0 = supine, last = prone, the middle ones linear.
    for k in range(frames):
        m = points(read(os.path.join(out, f"morph/morph_{k:03d}.vtp")))
        t = k / (frames - 1)
        check(maxdiff(m, [tuple((1 - t) * x + t * y for x, y in zip(p, q)) for p, q in zip(pts, pp)]) < 1e-3, f"morph frame {k} is not the interpolation at t = {t}")

    # K statistics agree with registration.vtp's.
    Ks = sorted(K)
    check(abs(report["dilatation"]["mean"] - sum(Ks) / len(Ks)) < 1e-9 and abs(report["dilatation"]["max"] - Ks[-1]) < 1e-12,
          f"K statistics {report['dilatation']}")
    check(report["dilatation"]["p99"] == Ks[round(0.99 * (len(Ks) - 1))], "K p99")

    # The measured claim: registration makes the prone curvature picture more like the supine.
    def correlations(rep, title):
        print(f"curvature correlation with the supine picture ({title}): segment unregistered registered")
        for x in NAMES:
            c = rep["segments"][x]["curvatureCorrelation"]
            print(f"  {x}  {c['unregistered']:+.3f}  {c['registered']:+.3f}")
        c = rep["curvatureCorrelation"]
        print(f"  all {c['unregistered']:+.3f}  {c['registered']:+.3f}")
        check(c["registered"] > c["unregistered"], f"{title}: registered correlation {c['registered']} not above unregistered {c['unregistered']}")
        better = sum(rep["segments"][x]["curvatureCorrelation"]["registered"] > rep["segments"][x]["curvatureCorrelation"]["unregistered"] for x in NAMES)
        print(f"  registered better in {better} of 5 segments")
    correlations(report, "conformal registration")

    # Harmonic registration: matched features drawn; correlation measured again.
    hreg = os.path.join(work, "harmonic")
    r = run_program(register, "--method", "harmonic", os.path.join(data, "supine"), os.path.join(data, "prone"), hreg)
    check(r.returncode == 0, f"harmonic registration: {r.stderr}")
    hout = os.path.join(work, "views-harmonic")
    r = views(hreg, hout, "--pixelsPerUnit", str(ppu), "--morphFrames", "2")
    check(r.returncode == 0 and r.stderr == "", f"harmonic views: {r.stderr}")
    hrep = json.load(open(os.path.join(hout, "flatviews.json")))
    hjson = json.load(open(os.path.join(hreg, "registration.json")))
    matched = sum(hjson["segments"][x]["features"]["matched"] for x in NAMES)
    check(hrep["features"]["matched"] == matched and matched > 0, f"matched features {hrep['features']} vs registration {matched}")
    check(hrep["features"]["found"] == 2 * matched, f"matched folds not all found by the detector: {hrep['features']}")
    print(f"harmonic: {matched} matched pairs of {hrep['features']['supine']} supine / {hrep['features']['prone']} prone folds")
    correlations(hrep, "harmonic registration")

    # Determinism: a second run gives identical files.
    out2 = os.path.join(work, "views2")
    views(reg, out2, "--pixelsPerUnit", str(ppu), "--morphFrames", str(frames))
    for name in PICTURES + ["distortion.vtp", "flatviews.json", "morph/morph_001.vtp", "distortion_3d.png", "textures_3d.png",
                            "morph/morph_001.png"]:
        check(filecmp.cmp(os.path.join(out, name), os.path.join(out2, name), shallow=False), f"{name} differs between runs")

    # Without an X display (a batch run), and with --skip3D: everything else, no 3D pictures, a
    # note on stdout (stderr stays empty: Slicer logs stderr as errors), the reason in the report.
    env = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
    for title, extra, environment in (("no display", [], env), ("--skip3D", ["--skip3D"], None)):
        o = os.path.join(work, "views-" + title.strip("-"))
        r = subprocess.run([exe, *extra, "--morphFrames", "2", "--pixelsPerUnit", "32", os.path.join(data, "supine"), os.path.join(data, "prone"), reg, o],
                           capture_output=True, text=True, stdin=subprocess.DEVNULL, env=environment)
        check(r.returncode == 0 and r.stderr == "", f"{title}: {r.returncode} {r.stderr!r}")
        check("3D pictures" in r.stdout and "not made" in r.stdout, f"{title}: no note on stdout")
        rep = json.load(open(os.path.join(o, "flatviews.json")))
        check(rep["views3D"].get("rendered") is False and rep["views3D"].get("reason"), f"{title}: views3D {rep['views3D']}")
        check(all(os.path.isfile(os.path.join(o, n)) for n in PICTURES + ["distortion.vtp", "morph/morph_001.vtp"]), f"{title}: outputs missing")
        check(not any(os.path.exists(os.path.join(o, n)) for n in ["distortion_3d.png", "textures_3d.png", "morph/morph_000.png"]),
              f"{title}: 3D pictures written")
        print(f"{title}: {rep['views3D']['reason']}")

    # Bad input: no registration.vtp. One stderr line naming it, non-zero exit, nothing written.
    partial = os.path.join(work, "reg-partial")
    shutil.copytree(reg, partial)
    os.remove(os.path.join(partial, "registration.vtp"))
    bad = os.path.join(work, "bad")
    r = views(partial, bad)
    check(r.returncode != 0 and len(r.stderr.strip().splitlines()) == 1 and "registration.vtp" in r.stderr and "does not exist" in r.stderr,
          f"missing registration.vtp: {r.returncode} {r.stderr!r}")
    check(not os.path.exists(bad), "output left after the error")
    r = views(reg, bad, "--morphFrames", "1")
    check(r.returncode != 0 and len(r.stderr.strip().splitlines()) == 1 and not os.path.exists(bad), f"morphFrames 1: {r.stderr!r}")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
