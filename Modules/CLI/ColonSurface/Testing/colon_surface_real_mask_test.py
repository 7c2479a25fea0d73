#!/usr/bin/env python3
"""A real colon's lumen mask as another tool delivers it (the Gut Cell Atlas colon voxelised at
2 mm: hundreds of handles where its loops and folds touch): ColonSurface makes it one closed
genus-0 surface in one call and says what it changed, and the whole pipeline runs on it as
label maps (ColonSupineProne --labelMaps, the mask as both scans).

Usage: colon_surface_real_mask_test.py <cli-modules folder> <ColonSurfaceMakeAtlasMask> <shared folder>
"""
import json
import os
import re
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

cli, maker, shared = sys.argv[1], sys.argv[2], sys.argv[3]
checks = Checks()
check = checks.check
work = tempfile.mkdtemp(prefix="colonmap-real-mask-test-")
try:
    mask = os.path.join(work, "gca_lumen.nii.gz")
    r = run_program(maker, os.path.join(shared, "data", "gca-00020"), mask, "2")
    check(r.returncode == 0, f"mask maker failed: {r.stderr}")
    m = re.search(r"components (\d+) handles (\d+)", r.stdout)
    handles = int(m.group(2)) if m else 0
    check(handles >= 3, f"the test mask should have handles: {r.stdout!r}")

    # ColonSurface, label only: one pass, closed genus 0, what changed in notes and return values.
    ret = os.path.join(work, "ret.txt")
    surface = os.path.join(work, "surface.vtp")
    r = run_program(os.path.join(cli, "ColonSurface"), "--returnparameterfile", ret, mask, surface)
    check(r.returncode == 0 and r.stderr == "", f"ColonSurface failed: {r.returncode} {r.stderr}")
    values = return_parameters(ret)
    check(values.get("topology") == "closed-genus-0", f"topology {values.get('topology')}")
    check(values.get("eulerCharacteristic") == "2", f"Euler characteristic {values.get('eulerCharacteristic')}")
    check(int(values.get("handlesCut", 0)) == handles, f"handles cut {values.get('handlesCut')} (mask: {handles})")
    check(int(values.get("voxelsChanged", 0)) > 0, "voxels changed not reported")
    check("handle(s) at their thinnest places" in r.stdout, "the note on cut handles is missing")
    check("contoured again" not in r.stdout and "steps: topology" in r.stdout,
          f"not one contouring pass: {r.stdout!r}")

    # The whole pipeline on label maps with handles.
    out = os.path.join(work, "out")
    r = run_program(os.path.join(cli, "ColonSupineProne"), "--supine", mask, "--prone", mask, "--labelMaps",
                    "--outputDirectory", out, "--skipViews")
    check(r.returncode == 0 and r.stderr == "", f"ColonSupineProne --labelMaps failed: {r.returncode} {r.stderr}")
    if r.returncode == 0:
        summary = json.load(open(os.path.join(out, "summary.json")))
        check(os.path.exists(os.path.join(out, "registration.vtp")), "no registration.vtp")
        check(any(s["name"].startswith("surface") for s in summary["stages"]), "no surface stage in summary.json")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
