#!/usr/bin/env python3
"""ColonTransferPoints on the phantom's true walls: a point lying exactly on a supine vertex lands
on that vertex's stored image (PronePosition); labels are kept; output valid markups (schema);
every point has an uncertainty; the true errors of the evaluation points are printed beside the
uncertainty estimate; supine -> prone -> supine round trip mean <= 1 mm; errors (missing
registration, missing registration_prone.vtp).

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
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

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

    # Errors.
    bad = os.path.join(work, "bad.mrk.json")
    res = run("--registration", os.path.join(work, "none.vtp"), "--input", vin, "--output", bad)
    check(res.returncode != 0 and "does not exist" in res.stderr and not os.path.exists(bad), f"missing registration: {res.stderr}")
    lonely = os.path.join(work, "lonely")
    os.makedirs(lonely)
    shutil.copy(reg, lonely)
    res = run("--registration", os.path.join(lonely, "registration.vtp"), "--input", vin, "--output", bad)
    check(res.returncode != 0 and "registration_prone.vtp" in res.stderr and not os.path.exists(bad), f"no prone mesh: {res.stderr}")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
