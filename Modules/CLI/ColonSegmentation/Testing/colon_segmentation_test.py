#!/usr/bin/env python3
"""ColonSegmentation as a user runs it: label map output and its geometry, return parameters,
determinism, the real CT's "no distended colon" failure (NIfTI and DICOM), bad inputs.

Usage: colon_segmentation_test.py <ColonSegmentation> <ColonPhantom> <shared folder>
"""
import filecmp
import gzip
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

exe, phantom, shared = sys.argv[1], sys.argv[2], sys.argv[3]
real = os.path.join(shared, "data", "totalseg-example-ct")
checks = Checks()
check = checks.check


def run(*args):
    return run_program(exe, *args)


def read_nrrd(path):
    """Header fields and raw voxels of a NRRD written by ITK (raw or gzip)."""
    data = open(path, "rb").read()
    end = data.index(b"\n\n")
    header = {}
    for line in data[:end].decode().splitlines()[1:]:
        if ":" in line and not line.startswith("#"):
            k, v = line.split(":", 1)
            header[k.strip()] = v.strip()
    body = data[end + 2:]
    if header.get("encoding") == "gzip":
        body = gzip.decompress(body)
    return header, body


returns = return_parameters


work = tempfile.mkdtemp(prefix="colonmap-segmentation-test-")
try:
    ph = os.path.join(work, "phantom")
    r = subprocess.run([phantom, "--outputDirectory", ph, "--seed", "4", "--spacing", "2.5,2.5,2.5", "--noFluid"],
                       capture_output=True, text=True)
    check(r.returncode == 0, f"phantom failed: {r.stderr}")
    ct = os.path.join(ph, "supine.nrrd")

    # A normal run: label map on the CT's grid, one lumen, return parameters, nothing on stderr.
    out, rp = os.path.join(work, "lumen.nrrd"), os.path.join(work, "rp.txt")
    r = run("--returnparameterfile", rp, ct, out)
    check(r.returncode == 0 and r.stderr == "", f"run failed: {r.returncode} {r.stderr}")
    h_ct, _ = read_nrrd(ct)
    h, voxels = read_nrrd(out)
    check(h.get("type") in ("unsigned char", "uchar", "uint8"), f"label type {h.get('type')}")
    for field in ("sizes", "space directions", "space origin"):
        check(h.get(field) == h_ct.get(field), f"label {field} {h.get(field)} != CT {h_ct.get(field)}")
    values = set(voxels)
    check(values == {0, 1}, f"label values {sorted(values)}")
    spacing = [float(x) for x in re.findall(r"[-0-9.e]+", h["space directions"])]
    voxel_ml = spacing[0] * spacing[4] * spacing[8] / 1000.0
    ml = voxels.count(1) * voxel_ml
    ret = returns(rp)
    check(set(ret) >= {"lumenVolume", "componentsKept", "componentsDropped", "droppedReasons",
                       "cavityVoxelsFilled", "handleVoxelsRemoved"}, f"return parameters {ret}")
    check(abs(float(ret.get("lumenVolume", "nan")) - ml) < 0.1, f"lumenVolume {ret.get('lumenVolume')} vs label {ml:.1f} ml")
    check(ret.get("componentsKept") == "1", "componentsKept")
    dropped = dict(kv.split(":") for kv in ret.get("droppedReasons", "").split(","))
    check(int(dropped.get("outsideBody", 0)) >= 1, f"outside air not dropped: {dropped}")
    check(sum(int(v) for v in dropped.values()) == int(ret.get("componentsDropped", -1)), "dropped counts add up")
    # The phantom colon holds well over a litre of gas (truth.json gives its shape, not volume).
    check(800 < ml < 4000, f"lumen volume {ml:.0f} ml")
    check("colon" in r.stdout and "outside body" in r.stdout, "report lines on stdout")

    # Same input, same bytes.
    out2 = os.path.join(work, "lumen2.nrrd")
    run(ct, out2)
    check(filecmp.cmp(out, out2, shallow=False), "two runs gave different label maps")

    # Options reach the method: an impossible minimum volume gives the clear failure.
    bad = os.path.join(work, "bad.nrrd")
    r = run("--minColonVolume", "5000", ct, bad)
    check(r.returncode != 0 and "no distended colon found" in r.stderr and r.stderr.count("\n") == 1,
          f"minColonVolume 5000: {r.stderr!r}")
    check(not os.path.exists(bad), "output left after a failure")

    # The real CT (3 mm abdomen, little bowel gas): one clear line, no output, NIfTI and DICOM.
    for name in ("example_ct.nii.gz", "example_ct_dicom"):
        r = run(os.path.join(real, name), bad)
        check(r.returncode != 0, f"{name}: exit code 0")
        check(r.stderr.count("\n") == 1 and "no distended colon found" in r.stderr and name in r.stderr
              and re.search(r"largest air component inside the body is [0-9.]+ ml", r.stderr) is not None,
              f"{name}: stderr {r.stderr!r}")
        check(not os.path.exists(bad), f"{name}: output written")

    # Bad inputs: missing file, folder without DICOM, a file that is no image.
    empty = os.path.join(work, "empty-folder")
    os.makedirs(empty)
    text = os.path.join(work, "notes.nrrd")
    open(text, "w").write("not an image\n")
    for path, needle in ((os.path.join(work, "missing.nrrd"), "missing.nrrd"), (empty, "empty-folder"),
                         (text, "notes.nrrd")):
        r = run(path, bad)
        check(r.returncode != 0 and r.stderr.count("\n") == 1 and needle in r.stderr and "input CT" in r.stderr,
              f"{path}: {r.returncode} {r.stderr!r}")
        check(not os.path.exists(bad), f"{path}: output written")
    r = run("--airThreshold", "50", ct, bad)
    check(r.returncode != 0 and "airThreshold" in r.stderr, f"airThreshold 50: {r.stderr!r}")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
