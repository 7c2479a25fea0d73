#!/usr/bin/env python3
"""ColonCleansing as a user runs it: outputs, return parameters, untagged scans, errors.

Usage: colon_cleansing_test.py <ColonCleansing> <ColonPhantom> <test data folder> <shared folder>
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

exe, phantom, data, shared = sys.argv[1:5]
checks = Checks()
check = checks.check


run = run_program


returns = return_parameters


work = tempfile.mkdtemp(prefix="colonmap-cleansing-test-")
try:
    # A fluid phantom: tagged material found and removed, both outputs written.
    ret = os.path.join(work, "ret.txt")
    r = run(exe, "--returnparameterfile", ret, "--taggedLabel", os.path.join(work, "tagged.nrrd"),
            os.path.join(data, "phantom-2.5mm", "supine.nrrd"), os.path.join(work, "clean.nrrd"))
    check(r.returncode == 0 and r.stderr == "", f"fluid phantom: {r.returncode} {r.stderr}")
    check(os.path.isfile(os.path.join(work, "clean.nrrd")) and os.path.isfile(os.path.join(work, "tagged.nrrd")),
          "outputs missing")
    values = returns(ret)
    check(int(values.get("cleansedVoxels", "0")) > 100, f"cleansedVoxels {values}")
    check(float(values.get("taggedVolume", "0")) > 1.0, f"taggedVolume {values}")
    m = re.search(r"gravity \(LPS\) (\S+),(\S+),(\S+) estimated", r.stdout)
    check(m is not None and float(m.group(2)) > 0.95, f"supine gravity not posterior: {m and m.group(0)}")

    # Given gravity overrides the estimate.
    r = run(exe, "--gravity", "anterior", os.path.join(data, "phantom-2.5mm", "prone.nrrd"), os.path.join(work, "p.nrrd"))
    check(r.returncode == 0 and re.search(r"gravity \(LPS\) -?0.00,-1.00,-?0.00 given", r.stdout) is not None,
          f"given gravity: {r.stdout[-300:]}")

    # An untagged scan passes through unchanged.
    dry = os.path.join(work, "dry")
    run(phantom, "--outputDirectory", dry, "--spacing", "5,5,5", "--noFluid")
    r = run(exe, "--returnparameterfile", ret, os.path.join(dry, "supine.nrrd"), os.path.join(work, "dry.nrrd"))
    check(r.returncode == 0 and "written unchanged" in r.stdout, f"untagged: {r.stdout[-200:]} {r.stderr}")
    check(returns(ret).get("cleansedVoxels") == "0", f"untagged changed voxels: {returns(ret)}")

    # The real CT (NIfTI and DICOM) reads and runs.
    real = os.path.join(shared, "data", "totalseg-example-ct")
    for source in ("example_ct.nii.gz", "example_ct_dicom"):
        r = run(exe, os.path.join(real, source), os.path.join(work, "real.nrrd"))
        check(r.returncode == 0 and r.stderr == "", f"real CT {source}: {r.returncode} {r.stderr}")

    # Bad input: one clear stderr line, non-zero exit, no output.
    bad_out = os.path.join(work, "bad.nrrd")
    notimage = os.path.join(work, "notes.json")
    open(notimage, "w").write("{}")
    for args, needle in (([os.path.join(work, "missing.nrrd"), bad_out], "file does not exist"),
                         ([notimage, bad_out], "unknown or unsupported image format"),
                         ([os.path.join(shared, "data"), bad_out], "no DICOM series"),
                         ([os.path.join(data, "phantom-2.5mm", "supine.nrrd"), os.path.join(work, "no", "x.nrrd")],
                          "its folder does not exist")):
        r = run(exe, *args)
        check(r.returncode != 0 and needle in r.stderr and r.stderr.count("\n") == 1, f"{args}: {r.stderr!r}")
        check(not os.path.exists(bad_out), f"{args}: output written")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
