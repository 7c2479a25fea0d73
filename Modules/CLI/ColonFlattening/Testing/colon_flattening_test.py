#!/usr/bin/env python3
"""ColonFlattening as a user runs it: outputs, flattening.json contents, determinism, options,
errors (missing folder, a missing segment or taeniae.vtp, folder without segments, a segment that is not a
cylinder).

Usage: colon_flattening_test.py <ColonFlattening> <ColonFlatteningMakeTestData> <fixture folder>
The fixture folder holds supine/ and prone/ landmarks folders cut from the phantom's true wall.
"""
import filecmp
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

exe, make_data, fixture = sys.argv[1], sys.argv[2], sys.argv[3]
checks = Checks()
check = checks.check
NAMES = ["A", "T", "D", "S", "R"]


def run(*args):
    return run_program(exe, *args)


returns = return_parameters


def nrrd_sizes(path):
    head = open(path, "rb").read(2000).split(b"\n\n")[0].decode("ascii", "replace")
    for line in head.splitlines():
        if line.startswith("sizes:"):
            return [int(v) for v in line.split(":")[1].split()]
    return []


work = tempfile.mkdtemp(prefix="colonmap-flattening-test-")
try:
    # Both scans of the phantom: all five segments, zero flips, small |mu|, v towards the cecum.
    for scan in ("supine", "prone"):
        out = os.path.join(work, scan)
        ret = os.path.join(work, scan + "-ret.txt")
        r = run("--returnparameterfile", ret, "--textures", os.path.join(fixture, scan), out)
        check(r.returncode == 0 and r.stderr == "", f"{scan} run: {r.returncode} {r.stderr}")
        check("<filter-end>" in r.stdout and "WARNING" not in r.stdout, f"{scan}: progress or warnings: {r.stdout[-600:]}")
        for x in NAMES:
            for name in (f"flat_{x}.vtp", f"surface_{x}.vtp", f"curvature_{x}.nrrd", f"curvature_{x}.png"):
                check(os.path.isfile(os.path.join(out, name)), f"{scan}: {name} missing")
            check(open(os.path.join(out, f"curvature_{x}.png"), "rb").read(8) == b"\x89PNG\r\n\x1a\n", f"{x}: not a PNG")
            header = open(os.path.join(out, f"flat_{x}.vtp"), "rb").read(6000)
            for array in (b'"FlatUV"', b'"Position3D"', b'"MeanCurvature"', b'"BeltramiAbs"', b'"Checkerboard"'):
                check(array in header, f"{scan} flat_{x}.vtp lacks {array}")
        rep = json.load(open(os.path.join(out, "flattening.json")))
        check(sorted(rep["segments"]) == sorted(NAMES) and rep["missingSegments"] == [], f"{scan}: segments {list(rep['segments'])}")
        check("times" not in rep["segments"]["A"], "times written without --reportTimes")
        landmarks = json.load(open(os.path.join(fixture, scan, "landmarks.json")))
        for x, s in rep["segments"].items():
            check(s["flippedTriangles"] == 0, f"{scan} {x}: {s['flippedTriangles']} flipped triangles")
            check(s["beltramiAbs"]["mean"] <= 0.02, f"{scan} {x}: mean |mu| {s['beltramiAbs']['mean']}")
            check(s["faces"] == landmarks["segments"][x]["faces"], f"{scan} {x}: faces {s['faces']}")
            check(s["cut"] == "TO", f"{scan} {x}: cut {s['cut']}")
            # The flat length of a tube is close to its length along the colon (the segment's
            # material length; conformal maps scale by the local circumference, hence the margin).
            true_len = landmarks["segments"][x]["lengthMm"]
            check(0.6 * true_len < s["lengthMm"] < 1.6 * true_len, f"{scan} {x}: length {s['lengthMm']} vs {true_len}")
            check(abs(s["flatWidth"] - 1.0) < 1e-12 and abs(s["flatLength"] - 1 / abs(s["lambda"])) < 1e-9,
                  f"{scan} {x}: unit width normalisation")
            check(abs(s["widthMm"] / abs(s["lambda"]) - s["lengthMm"]) < 1e-6 * s["lengthMm"], f"{x}: length = width / |lambda|")
            size = nrrd_sizes(os.path.join(out, f"curvature_{x}.nrrd"))
            check(size[:2] == s["image"]["size"] and abs(size[0] - s["widthMm"]) <= 1 and abs(size[1] - s["lengthMm"]) <= 1,
                  f"{scan} {x}: image size {size} for {s['widthMm']} x {s['lengthMm']} mm at 1 mm")
            check(s["image"]["filledPixels"] <= 0.001 * size[0] * size[1], f"{x}: {s['image']['filledPixels']} uncovered pixels")
        v = returns(ret)
        check(v.get("segments") == "5" and v.get("flippedTriangles") == "0", f"{scan} returns {v}")
        check(0 < float(v.get("worstMeanBeltrami", "1")) <= 0.02, f"{scan} worst mean |mu| {v.get('worstMeanBeltrami')}")

    # Same input, same bytes.
    again = os.path.join(work, "again")
    r = run("--textures", os.path.join(fixture, "supine"), again)
    a = os.path.join(work, "supine")
    check(r.returncode == 0 and all(filecmp.cmp(os.path.join(a, f), os.path.join(again, f), shallow=False)
                                    for f in os.listdir(a)), "two runs differ")

    # Options: circumference width, 2 mm pixels, Dirichlet cut, times in the report.
    opt = os.path.join(work, "opt")
    r = run("--widthMode", "circumference", "--mmPerPixel", "2", "--cutCondition", "dirichlet", "--reportTimes",
            os.path.join(fixture, "supine"), opt)
    check(r.returncode == 0, f"options run: {r.stderr}")
    rep = json.load(open(os.path.join(opt, "flattening.json")))
    base = json.load(open(os.path.join(work, "supine", "flattening.json")))
    for x, s in rep["segments"].items():
        check(abs(s["flatWidth"] - s["widthMm"]) < 1e-9, f"circumference mode {x}: flat width {s['flatWidth']}")
        check(abs(s["image"]["size"][0] - s["widthMm"] / 2) <= 1, f"2 mm pixels {x}: {s['image']['size']}")
        check(set(s["times"]) >= {"f1", "f2", "laplacian"}, f"times {x}: {s.get('times')}")
        check(s["beltramiAbs"]["mean"] > base["segments"][x]["beltramiAbs"]["mean"],
              f"{x}: the Dirichlet cut should distort more than the periodic one")
    check(rep["cutCondition"] == "dirichlet" and rep["widthMode"] == "circumference", "options not reported")

    # One subdivision: four times the faces on the same surface, |mu| about halved, no flips,
    # the same rectangle (width and length within the discretisation).
    sub = os.path.join(work, "sub")
    r = run("--subdivisions", "1", os.path.join(fixture, "supine"), sub)
    check(r.returncode == 0 and r.stderr == "", f"subdivisions run: {r.returncode} {r.stderr}")
    rep = json.load(open(os.path.join(sub, "flattening.json")))
    check(rep["subdivisions"] == 1 and base["subdivisions"] == 0, "subdivisions not reported")
    for x, s in rep["segments"].items():
        b = base["segments"][x]
        check(s["preparation"]["subdivisions"] == 1, f"subdivided {x}: preparation {s['preparation']}")
        check(s["faces"] >= 4 * landmarks["segments"][x]["faces"], f"subdivided {x}: {s['faces']} faces")
        check(s["flippedTriangles"] == 0, f"subdivided {x}: {s['flippedTriangles']} flips")
        check(0.3 * b["beltramiAbs"]["mean"] < s["beltramiAbs"]["mean"] < 0.7 * b["beltramiAbs"]["mean"],
              f"subdivided {x}: |mu| {s['beltramiAbs']['mean']} vs {b['beltramiAbs']['mean']}")
        check(abs(s["lengthMm"] - b["lengthMm"]) < 0.02 * b["lengthMm"] and abs(s["widthMm"] - b["widthMm"]) < 0.02 * b["widthMm"],
              f"subdivided {x}: {s['widthMm']} x {s['lengthMm']} vs {b['widthMm']} x {b['lengthMm']} mm")
    r = run("--subdivisions", "4", os.path.join(fixture, "supine"), os.path.join(work, "sub4"))
    check(r.returncode != 0 and "subdivisions" in r.stderr and not os.path.exists(os.path.join(work, "sub4")),
          f"--subdivisions 4: {r.returncode} {r.stderr!r}")

    # A missing segment or a missing taeniae.vtp: not a ColonLandmarks folder, refused (issue 24).
    partial = os.path.join(work, "partial-in")
    shutil.copytree(os.path.join(fixture, "supine"), partial)
    os.remove(os.path.join(partial, "segment_R.vtp"))
    out = os.path.join(work, "partial")
    r = run(partial, out)
    check(r.returncode == 1 and "segment_R.vtp is missing" in r.stderr and partial in r.stderr
          and len(r.stderr.strip().splitlines()) == 1 and not os.path.exists(out), f"missing segment: {r.returncode} {r.stderr!r}")
    notaeniae = os.path.join(work, "notaeniae-in")
    shutil.copytree(os.path.join(fixture, "supine"), notaeniae)
    os.remove(os.path.join(notaeniae, "taeniae.vtp"))
    out = os.path.join(work, "notaeniae")
    r = run(notaeniae, out)
    check(r.returncode == 1 and "taeniae.vtp is missing" in r.stderr and notaeniae in r.stderr
          and not os.path.exists(out), f"no taeniae: {r.returncode} {r.stderr!r}")

    # Errors: one stderr line naming the input, non-zero exit, no output folder left.
    holed = os.path.join(work, "holed")
    r = subprocess.run([make_data, holed, "3", "48", "2", "hole"], capture_output=True, text=True)
    check(r.returncode == 0, f"holed data: {r.stderr}")
    empty = os.path.join(work, "empty")
    os.makedirs(empty)
    for src, needle in ((os.path.join(work, "missing"), "does not exist"),
                        (empty, "holds none of segment_A.vtp"),
                        (os.path.join(holed, "supine"), "segment_T.vtp': not a topological cylinder")):
        bad = os.path.join(work, "bad-out")
        r = run(src, bad)
        lines = r.stderr.strip().splitlines()
        check(r.returncode != 0 and len(lines) == 1 and needle in lines[0], f"error for {src}: {r.returncode} {r.stderr!r}")
        check(not os.path.exists(bad), f"output left behind after the error for {src}")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
