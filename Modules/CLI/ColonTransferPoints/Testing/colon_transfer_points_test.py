#!/usr/bin/env python3
"""ColonTransferPoints on the phantom's true walls: a point lying exactly on a supine vertex lands
on that vertex's stored image (PronePosition); labels are kept; output valid markups (schema);
every point has an uncertainty; the true errors of the evaluation points are printed beside the
uncertainty estimate; supine -> prone -> supine round trip mean <= 1 mm; one registration file is
enough: a lone renamed copy as Slicer passes it gives byte-identical outputs in both directions to
runs given registration_prone.vtp; errors (missing registration, a registration without the prone
mesh inside and none beside it).

Usage: colon_transfer_points_test.py <ColonTransferPoints> <registration data folder>
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import vtk

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program, slicer_model_copy, without_field_data  # noqa: E402

exe, data = sys.argv[1], sys.argv[2]
reg = os.path.join(data, "registration", "registration.vtp")
checks = Checks()
check = checks.check


def run(*args):
    return run_program(exe, *args)


def points(path):
    j = json.load(open(path))
    m = j["markups"][0]
    sign = [-1, -1, 1] if m.get("coordinateSystem", "LPS") == "RAS" else [1, 1, 1]
    return [(c["label"], [s * v for s, v in zip(sign, c["position"])], c.get("description", "")) for c in m["controlPoints"]]


def write_points(path, pts):
    cps = [{"id": str(i + 1), "label": l, "position": list(p), "description": d} for i, (l, p, d) in enumerate(pts)]
    json.dump({"@schema": "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/Schema/markups-schema-v1.0.3.json#",
               "markups": [{"type": "Fiducial", "coordinateSystem": "LPS", "controlPoints": cps}]}, open(path, "w"))


work = tempfile.mkdtemp(prefix="colonmap-transfer-test-")
try:
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(reg)
    r.Update()
    pd = r.GetOutput()
    image = pd.GetPointData().GetArray("PronePosition")
    ids = range(0, pd.GetNumberOfPoints(), max(1, pd.GetNumberOfPoints() // 25))
    vin = os.path.join(work, "vertices.mrk.json")
    write_points(vin, [(f"V{i}", pd.GetPoint(i), "") for i in ids])
    vout = os.path.join(work, "vertices-prone.mrk.json")
    res = run("--registration", reg, "--input", vin, "--output", vout)
    check(res.returncode == 0 and res.stderr == "", f"vertex run: {res.stderr}")
    got = points(vout)
    dev = max(math.dist(p, image.GetTuple3(i)) for (l, p, d), i in zip(got, ids))
    print(f"points on supine vertices: largest distance from the stored image {dev:.2e} mm")
    check(dev < 1e-3, f"vertex transfer deviates by {dev} mm")
    check([l for l, p, d in got] == [f"V{i}" for i in ids], "labels kept in order")

    # Evaluation points: true errors vs the uncertainty estimate; round trip.
    out = os.path.join(work, "eval-prone.mrk.json")
    res = run("--registration", reg, "--input", os.path.join(data, "supine_eval.mrk.json"), "--output", out)
    check(res.returncode == 0 and res.stderr == "", f"eval run: {res.stderr}")
    try:
        import jsonschema
        schema = json.load(open(os.path.join(os.path.dirname(__file__), "..", "..", "..", "..", "..", "shared", "schemas",
                                             "markups-schema-v1.0.3.json")))
        jsonschema.validate(json.load(open(out)), schema)
        check(True, "schema")
    except FileNotFoundError:
        pass
    except Exception as e:  # noqa: BLE001
        check(False, f"markups schema: {e}")
    truth = {l: p for l, p, d in points(os.path.join(data, "prone_eval.mrk.json"))}
    mapped = points(out)
    errs, unc = [], []
    for l, p, d in mapped:
        m = re.search(r"uncertaintyMm=([0-9.]+)", d)
        check(m is not None, f"{l}: no uncertainty in '{d}'")
        check(re.search(r" reliable=(true|false) ", d) is not None, f"{l}: no reliable= in '{d}'")
        errs.append(math.dist(p, truth[l]))
        unc.append(float(m.group(1)) if m else 0.0)
    covered = sum(e <= u for e, u in zip(errs, unc)) / len(errs)
    me, mu = sum(errs) / len(errs), sum(unc) / len(unc)
    cov = sum((e - me) * (u - mu) for e, u in zip(errs, unc))
    corr = cov / math.sqrt(sum((e - me) ** 2 for e in errs) * sum((u - mu) ** 2 for u in unc) or 1)
    print(f"evaluation points: true error mean {me:.2f} mm, uncertainty mean {mu:.2f} mm, "
          f"error <= uncertainty for {100 * covered:.0f}%, correlation {corr:.2f}")
    back = os.path.join(work, "eval-back.mrk.json")
    res = run("--registration", reg, "--input", out, "--output", back, "--direction", "proneToSupine")
    check(res.returncode == 0 and res.stderr == "", f"back run: {res.stderr}")
    start = {l: p for l, p, d in points(os.path.join(data, "supine_eval.mrk.json"))}
    rt = [math.dist(p, start[l]) for l, p, d in points(back)]
    print(f"round trip supine -> prone -> supine: mean {sum(rt) / len(rt):.3f} mm, max {max(rt):.3f} mm")
    check(sum(rt) / len(rt) <= 1.0, f"round trip mean {sum(rt) / len(rt)}")

    # One file is enough (issue 23): the registration as Slicer passes a model node, a renamed copy
    # alone in its temp folder, against runs given the prone mesh file explicitly.
    slicer_tmp = os.path.join(work, "SlicerTemp")
    os.makedirs(slicer_tmp)
    lone = os.path.join(slicer_tmp, "CFHJE_vtkMRMLModelNodeE.vtp")
    slicer_model_copy(reg, lone)
    prone_mesh = os.path.join(data, "registration", "registration_prone.vtp")
    identical = 0
    for direction, source in (("supineToProne", "supine_eval"), ("proneToSupine", "prone_eval"),
                              ("supineToProne", "supine_polyps"), ("proneToSupine", "prone_polyps")):
        given, alone = os.path.join(work, f"{source}-given.mrk.json"), os.path.join(work, f"{source}-alone.mrk.json")
        src = os.path.join(data, source + ".mrk.json")
        a = run("--registration", reg, "--proneMesh", prone_mesh, "--input", src, "--output", given, "--direction", direction)
        b = run("--registration", lone, "--input", src, "--output", alone, "--direction", direction)
        check(a.returncode == 0 and b.returncode == 0 and b.stderr == "", f"{source} alone: {a.stderr} {b.stderr}")
        same = os.path.isfile(given) and os.path.isfile(alone) and open(given, "rb").read() == open(alone, "rb").read()
        identical += check(same, f"{direction} {source}: the lone renamed registration gives other results than with registration_prone.vtp")
    print(f"lone renamed registration (Slicer's temporary copy): {identical} of 4 outputs byte-identical (both directions)")

    # Errors.
    bad = os.path.join(work, "bad.mrk.json")
    res = run("--registration", os.path.join(work, "none.vtp"), "--input", vin, "--output", bad)
    check(res.returncode != 0 and "does not exist" in res.stderr and not os.path.exists(bad), f"missing registration: {res.stderr}")
    old = os.path.join(work, "old")
    os.makedirs(old)
    without_field_data(reg, os.path.join(old, "registration.vtp"))
    res = run("--registration", os.path.join(old, "registration.vtp"), "--input", vin, "--output", bad)
    check(res.returncode != 0 and "carries no prone mesh" in res.stderr and "registration_prone.vtp" in res.stderr
          and len(res.stderr.strip().splitlines()) == 1 and not os.path.exists(bad), f"no prone mesh: {res.stderr}")
    # ... but an old registration still works with its registration_prone.vtp beside it.
    shutil.copy(prone_mesh, old)
    old_out = os.path.join(work, "old-out.mrk.json")
    res = run("--registration", os.path.join(old, "registration.vtp"), "--input", os.path.join(data, "prone_eval.mrk.json"),
              "--output", old_out, "--direction", "proneToSupine")
    check(res.returncode == 0 and open(old_out, "rb").read() == open(os.path.join(work, "prone_eval-given.mrk.json"), "rb").read(),
          f"old registration with its sibling: {res.stderr}")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
