#!/usr/bin/env python3
"""ColonPhantom as a user runs it: outputs, their formats and consistency, determinism, errors.

Usage: colon_phantom_test.py <ColonPhantom executable> <shared folder>
"""
import filecmp
import json
import os
import shutil
import subprocess
import sys
import tempfile

import jsonschema

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

exe, shared = sys.argv[1], sys.argv[2]
schema = json.load(open(os.path.join(shared, "schemas", "markups-schema-v1.0.3.json")))
checks = Checks()
check = checks.check


def run(*args):
    return run_program(exe, *args)


work = tempfile.mkdtemp(prefix="colonmap-phantom-test-")
try:
    a, b = os.path.join(work, "a"), os.path.join(work, "b")
    common = ["--seed", "5", "--spacing", "4,4,4", "--deformation", "0.5"]
    r = run("--outputDirectory", a, *common)
    check(r.returncode == 0 and r.stderr == "", f"run failed: {r.returncode} {r.stderr}")
    r2 = run("--outputDirectory", b, *common)
    check(r2.returncode == 0, "second run failed")
    names = sorted(os.listdir(a))
    check(names == sorted(os.listdir(b)), "two runs wrote different file sets")
    match, mismatch, errors = filecmp.cmpfiles(a, b, names, shallow=False)
    check(not mismatch and not errors, f"same seed and options, different bytes: {mismatch}")

    # Markups are valid Slicer markups; supine and prone carry the same labels.
    for kind in ("polyps", "eval", "centerline", "flexures"):
        docs = {}
        for posture in ("supine", "prone"):
            doc = json.load(open(os.path.join(a, f"{posture}_{kind}.mrk.json")))
            try:
                jsonschema.validate(doc, schema)
                check(True, "")
            except jsonschema.ValidationError as e:
                check(False, f"{posture}_{kind}.mrk.json does not validate: {e.message}")
            docs[posture] = [p["label"] for p in doc["markups"][0]["controlPoints"]]
        if kind != "centerline":  # a curve sampled by each scan's own arc length
            check(docs["supine"] == docs["prone"] and docs["supine"], f"{kind}: labels differ between scans")
    flex = json.load(open(os.path.join(a, "supine_flexures.mrk.json")))["markups"][0]["controlPoints"]
    check([p["label"] for p in flex] == ["HF", "SF", "DSJ", "RSJ"], "flexure labels")
    z = {p["label"]: p["position"][2] for p in flex}
    check(z["SF"] == max(z.values()), "splenic flexure is not the highest flexure")

    truth = json.load(open(os.path.join(a, "truth.json")))
    check(1200 <= truth["colonLengthMm"] <= 1600, f"colon length {truth['colonLengthMm']}")
    check(set(truth["segments"]) == {"A", "T", "D", "S", "R"}, "segments in truth.json")
    polyps = json.load(open(os.path.join(a, "supine_polyps.mrk.json")))["markups"][0]["controlPoints"]
    check(len(polyps) == len(truth["polyps"]) > 0, "polyp count")

    # A different seed gives a different colon.
    c = os.path.join(work, "c")
    run("--outputDirectory", c, "--seed", "6", "--spacing", "4,4,4")
    check(not filecmp.cmp(os.path.join(a, "supine_truth.vtp"), os.path.join(c, "supine_truth.vtp"), shallow=False),
          "different seeds gave the same wall")

    # Bad input: one stderr line naming the parameter, non-zero exit, nothing written.
    for args, needle in ((["--deformation", "2"], "--deformation"),
                         (["--spacing", "1,1"], "--spacing"),
                         (["--spacing", "nan,1,1"], "--spacing"),
                         (["--seed", "-1"], "--seed")):
        d = os.path.join(work, "bad")
        r = run("--outputDirectory", d, *args)
        check(r.returncode != 0, f"{args}: exit code 0")
        check(r.stderr.count("\n") == 1 and needle in r.stderr, f"{args}: stderr {r.stderr!r}")
        check(not os.path.exists(d), f"{args}: output folder created")
    blocked = os.path.join(work, "file-not-folder")
    open(blocked, "w").write("x")
    r = run("--outputDirectory", blocked, "--spacing", "5,5,5")
    check(r.returncode != 0 and "exists and is not a folder" in r.stderr, f"file as output folder: {r.stderr!r}")
    r = run("--outputDirectory", "/proc/colonmap-cannot-write", "--spacing", "5,5,5")
    check(r.returncode != 0 and r.stderr.count("\n") == 1, f"unwritable output folder: {r.stderr!r}")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
