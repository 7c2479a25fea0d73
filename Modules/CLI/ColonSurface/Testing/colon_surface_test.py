#!/usr/bin/env python3
"""ColonSurface as a user runs it: outputs, return parameters, determinism, label types, errors.

Usage: colon_surface_test.py <ColonSurface executable> <ColonSurfaceMakeTestData executable>
"""
import filecmp
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

exe, make_data = sys.argv[1], sys.argv[2]
checks = Checks()
check = checks.check


def run(*args):
    return run_program(exe, *args)


returns = return_parameters


def vtp_header(path):
    data = open(path, "rb").read()
    return data[:data.find(b"<AppendedData")].decode("utf-8", "replace")


work = tempfile.mkdtemp(prefix="colonmap-surface-test-")
try:
    data = os.path.join(work, "data")
    r = subprocess.run([make_data, data, "2.5", "2"], capture_output=True, text=True)
    check(r.returncode == 0, f"test data: {r.stderr}")
    label, label3, ct = (os.path.join(data, n) for n in ("label.nrrd", "label3.nrrd", "ct.nrrd"))

    # Label + CT: one closed genus-0 surface near the target size, with MeanCurvature.
    out = os.path.join(work, "out")
    os.makedirs(out)
    a, b, ret = os.path.join(out, "a.vtp"), os.path.join(out, "b.vtp"), os.path.join(out, "ret.txt")
    r = run("--returnparameterfile", ret, "--referenceCT", ct, "--targetFaces", "15000", label, a)
    check(r.returncode == 0 and r.stderr == "", f"label+CT run: {r.returncode} {r.stderr}")
    check("<filter-end>" in r.stdout and "genus 0" in r.stdout and "CT iso-value" in r.stdout,
          f"progress tags or notes missing: {r.stdout[-400:]}")
    v = returns(ret)
    check(abs(int(v.get("faces", 0)) - 15000) <= 750, f"faces {v.get('faces')}")
    check(v.get("eulerCharacteristic") == "2", f"Euler characteristic {v.get('eulerCharacteristic')}")
    check(v.get("topology") == "closed-genus-0", f"topology {v.get('topology')!r}")
    header = vtp_header(a)
    check('Name="MeanCurvature"' in header, "no MeanCurvature point array")
    m = re.search(r'NumberOfPolys="(\d+)"', header)
    check(m is not None and m.group(1) == v.get("faces"), "face count in the file differs from the return value")

    # Same inputs, same bytes.
    r = run("--referenceCT", ct, "--targetFaces", "15000", label, b)
    check(r.returncode == 0 and filecmp.cmp(a, b, shallow=False), "two runs differ")

    # A short label map with lumen value 3, label only (no CT).
    c = os.path.join(out, "c.vtp")
    r = run("--labelValue", "3", "--returnparameterfile", ret, "--targetFaces", "8000", label3, c)
    check(r.returncode == 0 and os.path.isfile(c), f"labelValue 3: {r.stderr}")
    check(returns(ret).get("topology") == "closed-genus-0", f"label only topology {returns(ret).get('topology')!r}")

    # Errors: one stderr line naming the input, non-zero exit, no output.
    bad = os.path.join(out, "bad.vtp")
    for args, needle in (([os.path.join(work, "missing.nrrd"), bad], "missing.nrrd"),
                         ([a, bad], "a.vtp"),                      # a surface given as the label map
                         (["--labelValue", "9", label, bad], "no voxel has the label value 9"),
                         (["--referenceCT", os.path.join(work, "nope.nrrd"), label, bad], "nope.nrrd"),
                         (["--targetFaces", "5", label, bad], "targetFaces")):
        r = run(*args)
        check(r.returncode != 0, f"{args}: exit code 0")
        check(r.stderr.count("\n") == 1 and needle in r.stderr, f"{args}: stderr {r.stderr!r}")
        check(not os.path.exists(bad), f"{args}: output written")
        check(not [f for f in os.listdir(out) if f.startswith(".colonmap-tmp")], f"{args}: temporaries left")

    # A CT on another grid.
    other = os.path.join(work, "other")
    subprocess.run([make_data, other, "3.0", "3"], capture_output=True)
    r = run("--referenceCT", os.path.join(other, "ct.nrrd"), label, bad)
    check(r.returncode != 0 and "grid" in r.stderr and r.stderr.count("\n") == 1, f"other grid: {r.stderr!r}")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
