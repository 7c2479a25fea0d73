#!/usr/bin/env python3
"""ColonEvaluateRegistration on the phantom's true walls: the conformal baseline and the centerline
arc-length baseline evaluated on the phantom's evaluation points and polyps (the table is printed),
errors.json / errors.tsv contents, round trip <= 1 mm, the same errors.json and errors.tsv (byte for
byte) from a lone renamed registration as Slicer passes it, and errors (no common labels, missing
file, a registration without the prone mesh inside and none beside it).

Usage: colon_evaluate_registration_test.py <ColonEvaluateRegistration> <registration data folder>
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program, slicer_model_copy, without_field_data  # noqa: E402

exe, data = sys.argv[1], sys.argv[2]
checks = Checks()
check = checks.check


def run(*args):
    return run_program(exe, *args)


work = tempfile.mkdtemp(prefix="colonmap-evaluate-test-")
try:
    reports = {}
    for method, folder in (("conformal", "registration"), ("centerline", "registration-centerline")):
        out = os.path.join(work, method + ".json")
        r = run("--registration", os.path.join(data, folder, "registration.vtp"),
                "--truthSupine", os.path.join(data, "supine_eval.mrk.json"), "--truthProne", os.path.join(data, "prone_eval.mrk.json"),
                "--polypsSupine", os.path.join(data, "supine_polyps.mrk.json"), "--polypsProne", os.path.join(data, "prone_polyps.mrk.json"),
                "--output", out)
        check(r.returncode == 0 and r.stderr == "", f"{method}: {r.returncode} {r.stderr}")
        tsv = os.path.join(work, method + ".tsv")
        check(os.path.isfile(tsv), f"{method}: no table")
        print(f"== {method} baseline (3D error mm, flat error width 1)")
        print(open(tsv).read().rstrip())
        j = json.load(open(out))
        reports[method] = j
        check(set(j["segments"]) == set("ATDSR"), f"{method}: segments {list(j['segments'])}")
        check(j["overall"]["error3D"]["count"] > 0 and j["unmatchedLabels"] == 0, f"{method}: counts")
        check("polyps" in j and j["polyps"]["error3D"]["count"] > 0, f"{method}: polyps")
        check(j["overall"]["roundTrip"]["mean"] <= 1.0, f"{method}: round trip {j['overall']['roundTrip']['mean']}")
        s = j["overall"]["error3D"]
        check(s["median"] <= s["p90"] <= s["max"], f"{method}: statistics order")
        u = j["overall"]["uncertainty"]
        print(f"uncertainty: mean {u['mean']:.2f} mm, coverage {u['coverage']:.2f}, correlation with error {u['correlationWithError']:.2f}")
    # One file is enough (issue 23): a lone renamed copy as Slicer passes it, against a run given
    # registration_prone.vtp explicitly.
    reg = os.path.join(data, "registration", "registration.vtp")
    truth = ["--truthSupine", os.path.join(data, "supine_eval.mrk.json"), "--truthProne", os.path.join(data, "prone_eval.mrk.json"),
             "--polypsSupine", os.path.join(data, "supine_polyps.mrk.json"), "--polypsProne", os.path.join(data, "prone_polyps.mrk.json")]
    slicer_tmp = os.path.join(work, "SlicerTemp")
    os.makedirs(slicer_tmp)
    lone = os.path.join(slicer_tmp, "CFHJE_vtkMRMLModelNodeE.vtp")
    slicer_model_copy(reg, lone)
    given = os.path.join(work, "given.json")
    alone = os.path.join(work, "alone.json")
    a = run("--registration", reg, "--proneMesh", os.path.join(data, "registration", "registration_prone.vtp"), *truth,
            "--output", given)
    b = run("--registration", lone, *truth, "--output", alone)
    check(a.returncode == 0 and b.returncode == 0 and b.stderr == "", f"lone registration: {a.stderr} {b.stderr}")
    for ext in (".json", ".tsv"):
        g, l = given[:-5] + ext, alone[:-5] + ext
        check(os.path.isfile(g) and os.path.isfile(l) and open(g, "rb").read() == open(l, "rb").read(),
              f"errors{ext} from the lone renamed registration differs from the run given registration_prone.vtp")
    old = os.path.join(work, "old")
    os.makedirs(old)
    without_field_data(reg, os.path.join(old, "registration.vtp"))
    bad = os.path.join(work, "bad.json")
    r = run("--registration", os.path.join(old, "registration.vtp"), *truth, "--output", bad)
    check(r.returncode != 0 and "carries no prone mesh" in r.stderr and len(r.stderr.strip().splitlines()) == 1
          and not os.path.exists(bad), f"no prone mesh: {r.stderr}")

    # Errors: no label in common; missing truth file.
    other = os.path.join(work, "other.mrk.json")
    j = json.load(open(os.path.join(data, "prone_eval.mrk.json")))
    for c in j["markups"][0]["controlPoints"]:
        c["label"] = "X" + c["label"]
    json.dump(j, open(other, "w"))
    r = run("--registration", os.path.join(data, "registration", "registration.vtp"),
            "--truthSupine", os.path.join(data, "supine_eval.mrk.json"), "--truthProne", other, "--output", bad)
    check(r.returncode != 0 and "no label in common" in r.stderr and not os.path.exists(bad), f"labels: {r.stderr}")
    r = run("--registration", os.path.join(data, "registration", "registration.vtp"),
            "--truthSupine", os.path.join(work, "none.mrk.json"), "--truthProne", other, "--output", bad)
    check(r.returncode != 0 and len(r.stderr.strip().splitlines()) == 1 and not os.path.exists(bad), f"missing: {r.stderr}")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
