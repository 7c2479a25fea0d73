#!/usr/bin/env python3
"""ColonPhantom --realColon as a user runs it (issue 17): a pair from each kind of atlas in the
shared data, its files and their consistency, determinism, and errors for bad real-colon inputs.

Usage: real_colon_phantom_test.py <ColonPhantom executable> <shared folder>
"""
import filecmp
import json
import math
import os
import shutil
import sys
import tempfile

import jsonschema

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

exe, shared = sys.argv[1], sys.argv[2]
data = os.path.join(shared, "data")
schema = json.load(open(os.path.join(shared, "schemas", "markups-schema-v1.0.3.json")))
checks = Checks()
check = checks.check
EXPECTED = sorted(["supine.nrrd", "prone.nrrd", "supine_truth.vtp", "prone_truth.vtp", "supine_polyps.mrk.json",
                   "prone_polyps.mrk.json", "supine_eval.mrk.json", "prone_eval.mrk.json", "supine_centerline.mrk.json",
                   "prone_centerline.mrk.json", "supine_flexures.mrk.json", "prone_flexures.mrk.json", "truth.json"])


def points(folder, name):
    doc = json.load(open(os.path.join(folder, name)))
    return doc, {p["label"]: p for p in doc["markups"][0]["controlPoints"]}


work = tempfile.mkdtemp(prefix="colonmap-real-phantom-test-")
try:
    # HuBMAP female colon, twice: the same bytes.
    a, b = os.path.join(work, "a"), os.path.join(work, "b")
    common = ["--realColon", os.path.join(data, "hubmap-vhf-00080"), "--seed", "2", "--spacing", "4,4,4"]
    ret = os.path.join(work, "ret.txt")
    r = run_program(exe, "--returnparameterfile", ret, "--outputDirectory", a, *common)
    check(r.returncode == 0 and r.stderr == "", f"run failed: {r.returncode} {r.stderr}")
    r2 = run_program(exe, "--outputDirectory", b, *common)
    check(r2.returncode == 0, f"second run failed: {r2.stderr}")
    names = sorted(os.listdir(a))
    check(names == EXPECTED, f"files: {names}")
    match, mismatch, errors = filecmp.cmpfiles(a, b, names, shallow=False)
    check(not mismatch and not errors, f"same seed and options, different bytes: {mismatch}")
    values = return_parameters(ret)
    check(800 < float(values.get("colonLength", 0)) < 1100, f"return parameters {values}")

    # Markups: valid, same labels in both scans; each evaluation point moved by the deformation.
    for kind in ("polyps", "eval", "centerline", "flexures"):
        labels = {}
        for posture in ("supine", "prone"):
            doc, pts = points(a, f"{posture}_{kind}.mrk.json")
            try:
                jsonschema.validate(doc, schema)
            except jsonschema.ValidationError as e:
                check(False, f"{posture}_{kind}.mrk.json does not validate: {e.message}")
            labels[posture] = list(pts)
        check(labels["supine"] == labels["prone"] and labels["supine"], f"{kind}: labels differ between scans")
    _, sup = points(a, "supine_eval.mrk.json")
    _, pro = points(a, "prone_eval.mrk.json")
    moved = [math.dist(sup[k]["position"], pro[k]["position"]) for k in sup]
    mean = sum(moved) / len(moved)
    truth = json.load(open(os.path.join(a, "truth.json")))
    check(abs(truth["noRegistration"]["mean"] - mean) < 1e-3, "truth.json's no-registration mean is not the evaluation points'")
    check(7.0 < mean < 20.0, f"no-registration mean {mean:.1f} mm")
    _, flex = points(a, "supine_flexures.mrk.json")
    check(list(flex) == ["HF", "SF", "DSJ", "RSJ"], "flexure labels")
    s = [float(p["description"].split("s=")[1].split()[0]) for p in flex.values()]
    check(s == sorted(s), f"flexures not in order along the colon: {s}")
    check(truth["generator"] == "ColonPhantom --realColon" and "HuBMAP" in truth["source"]["credit"], "truth.json source")
    check(truth["taeniae"] is None, "taeniae should be unknown on a real colon")
    check(truth["embedding"]["supineCrossingFacePairs"] == 0 and truth["embedding"]["proneCrossingFacePairs"] == 0,
          "surfaces not embedded")
    check(truth["materialCoordinates"]["localExtrema"] == 0 and truth["materialCoordinates"]["maxCurvesPerLevel"] == 1,
          "material s not monotone")
    check(truth["maxLocalStretch"] <= 0.15, f"local stretch {truth['maxLocalStretch']}")
    check(set(truth["segments"]) == set("ATDSR"), "segments")
    check("assumed" not in truth["flexures"]["RSJ"]["source"], "HuBMAP has a Rectum piece: the RSJ is not assumed")

    # The GCA colon (voxel units, its RSJ assumed) at a coarse spacing.
    g = os.path.join(work, "g")
    r = run_program(exe, "--outputDirectory", g, "--realColon", os.path.join(data, "gca-00020"), "--spacing", "5,5,5")
    check(r.returncode == 0 and r.stderr == "", f"GCA run failed: {r.stderr}")
    if r.returncode == 0:
        tg = json.load(open(os.path.join(g, "truth.json")))
        check("EdinGCA_3D_00020" in tg["source"]["credit"], "GCA credit")
        check(2000 < tg["colonLengthMm"] < 2500, f"GCA length {tg['colonLengthMm']}")
        check("assumed" in tg["flexures"]["RSJ"]["source"], "GCA has no RSJ landmark: it must say the RSJ is assumed")

    # Bad real-colon inputs: one stderr line naming the input, non-zero exit, nothing written.
    own = os.path.join(work, "own")
    os.makedirs(own)
    # A valid surface that is not closed: one triangle.
    open(os.path.join(own, "lumen.vtk"), "w").write("# vtk DataFile Version 3.0\nopen\nASCII\nDATASET POLYDATA\n"
                                                     "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 2\n")
    open(os.path.join(own, "midline.mrk.json"), "w").write("{}")
    open(os.path.join(own, "flexures.mrk.json"), "w").write("{}")
    for source, needle in ((os.path.join(work, "missing"), "missing"),
                           (os.path.join(data, "totalseg-example-ct"), "totalseg-example-ct"),
                           (own, "lumen.vtk")):
        d = os.path.join(work, "bad")
        r = run_program(exe, "--outputDirectory", d, "--realColon", source, "--spacing", "5,5,5")
        check(r.returncode != 0, f"{source}: exit code 0")
        check(r.stderr.count("\n") == 1 and needle in r.stderr, f"{source}: stderr {r.stderr!r}")
        check(not os.path.exists(d) or not os.listdir(d), f"{source}: output written")
    r = run_program(exe, "--outputDirectory", os.path.join(work, "bad2"), "--realColon", os.path.join(data, "gca-00020"),
                    "--trueWallGrid", "0.1")
    check(r.returncode != 0 and "--trueWallGrid" in r.stderr, f"bad grid: {r.stderr!r}")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
