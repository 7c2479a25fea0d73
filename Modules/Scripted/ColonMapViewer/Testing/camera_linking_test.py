#!/usr/bin/env python3
"""ColonMapViewer's logic outside 3D Slicer (numpy + VTK, Debian's python3-vtk9), issue 23:

- the same camera poses as ColonEndoluminalViews' cameras.json for the same findings (each phantom
  polyp of the registration test data): supine and prone position within 0.5 mm, view direction
  and view-up within 0.5 degrees, both from the finding (the list's jump) and from the supine pose
  (the live link); a supine camera turned by 20 degrees must not pass;
- on a tube whose prone wall is the supine one shifted by 10 mm, every linked camera is the supine
  one shifted by 10 mm, whatever its direction (exact answer); RAS <-> LPS round trip;
- one update (supine pose -> prone pose) takes at most 20 ms: median and 90th percentile over 200
  poses along the colon;
- a run folder is read as ColonSupineProne writes it; a folder without registration.vtp is refused.

Usage: camera_linking_test.py <ColonEndoluminalViews> <TestData folder>
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, ".."))
sys.path.insert(0, os.path.join(here, *[".."] * 4, "Testing", "Python"))
from ColonMapViewerLib.CameraLinking import CameraLinker, CameraPose, RegistrationSurface, lps_to_ras, ras_to_lps  # noqa: E402
from ColonMapViewerLib.RunFolder import RunFolder  # noqa: E402
from ColonMapViewerLib.SyntheticRegistration import tube_registration  # noqa: E402
from colonmap_testing import Checks  # noqa: E402

exe, data = sys.argv[1], sys.argv[2]
checks = Checks()
check = checks.check
MM, DEG = 0.5, 0.5


def angle(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return math.degrees(math.atan2(np.linalg.norm(np.cross(a, b)), a @ b))


def differences(p, q):
    """(position mm, view direction degrees, view-up degrees) between two poses."""
    return (float(np.linalg.norm(p.position - q.position)),
            angle(p.focal_point - p.position, q.focal_point - q.position), angle(p.view_up, q.view_up))


def pose(j):
    return CameraPose(j["position"], j["focalPoint"], j["viewUp"])


def yawed(p, degrees):
    """The pose turned about its own view-up through its position (Rodrigues)."""
    k = p.view_up / np.linalg.norm(p.view_up)
    f = p.focal_point - p.position
    t = math.radians(degrees)
    r = f * math.cos(t) + np.cross(k, f) * math.sin(t) + k * (k @ f) * (1 - math.cos(t))
    return CameraPose(p.position, p.position + r, p.view_up)


work = tempfile.mkdtemp(prefix="colonmap-viewer-test-")
try:
    reg_data = os.path.join(data, "registration-2mm-96")
    registration = os.path.join(reg_data, "registration", "registration.vtp")
    findings = os.path.join(reg_data, "supine_polyps.mrk.json")
    views = os.path.join(work, "views")
    r = subprocess.run([exe, "--supineVolume", os.path.join(data, "phantom-2.5mm", "supine.nrrd"),
                        "--proneVolume", os.path.join(data, "phantom-2.5mm", "prone.nrrd"), "--registration", registration,
                        "--findings", findings, "--imageSize", "32,32", views],
                       capture_output=True, text=True, stdin=subprocess.DEVNULL)
    if not check(r.returncode == 0, f"ColonEndoluminalViews: {r.stderr}"):
        sys.exit(checks.finish())
    cameras = json.load(open(os.path.join(views, "cameras.json")))
    distance = 25.0  # ColonEndoluminalViews' default --cameraDistance
    started = time.perf_counter()
    linker = CameraLinker.from_file(registration)
    print(f"linker built in {time.perf_counter() - started:.2f} s")

    # Same poses as cameras.json, for the same findings.
    points = {c["label"]: c["position"] for c in json.load(open(findings))["markups"][0]["controlPoints"]}
    worst = [0.0, 0.0]
    for v in cameras["views"]:
        label = v["label"]
        s, p = linker.link_finding(np.array(points[label]), distance)
        _, live = linker.link_camera(pose(v["supine"]))
        for what, mine, theirs in (("supine", s, v["supine"]), ("prone", p, v["prone"]), ("prone (live)", live, v["prone"])):
            mm, view_deg, up_deg = differences(mine, pose(theirs))
            worst = [max(worst[0], mm), max(worst[1], view_deg, up_deg)]
            check(mm <= MM and view_deg <= DEG and up_deg <= DEG,
                  f"{label} {what}: {mm:.3g} mm, view {view_deg:.3g} deg, up {up_deg:.3g} deg from cameras.json")
        # A supine camera turned by 20 degrees gives another prone camera (the comparison can fail).
        _, turned = linker.link_camera(yawed(pose(v["supine"]), 20.0))
        mm, view_deg, _ = differences(turned, pose(v["prone"]))
        check(view_deg > 5 * DEG, f"{label}: a supine camera turned 20 deg still matches ({view_deg:.2f} deg)")
    print(f"{len(cameras['views'])} views against cameras.json: largest difference {worst[0]:.2e} mm, {worst[1]:.2e} deg")

    # Exact answer: the prone wall is the supine one shifted by 10 mm.
    shift = np.array([10.0, 0.0, 0.0])
    tube = CameraLinker(RegistrationSurface(tube_registration(shift=tuple(shift))))
    largest = 0.0
    for o, f, up in (([1, 2, 100], [3, -4, 140], [0, 1, 0.3]), ([-5, 0, 60], [10, 3, 70], [0, 0, 1]),
                     ([0, 0, 200], [0, 10, 150], [1, 0, 0])):
        s, p = tube.link_camera(CameraPose(o, f, up))
        largest = max(largest, np.linalg.norm(p.position - s.position - shift), np.linalg.norm(p.focal_point - s.focal_point - shift),
                      np.linalg.norm(p.view_up - s.view_up))
    s, p = tube.link_finding(np.array([15.9, 0.0, 150.0]), distance)
    largest = max(largest, np.linalg.norm(p.position - s.position - shift))
    print(f"shifted tube: linked cameras off the shifted supine cameras by at most {largest:.1e}")
    check(largest < 1e-6, f"shifted tube: {largest}")
    ras = lps_to_ras(CameraPose([1, 2, 3], [4, 5, 6], [0, 0, 1]))
    check(np.allclose(ras.position, [-1, -2, 3]) and np.allclose(ras_to_lps(ras).focal_point, [4, 5, 6]), "RAS <-> LPS")

    # One update: poses along the colon, looking 20 mm ahead.
    sk = linker.skeleton
    times = []
    for arc in np.linspace(10.0, sk.arc[-1] - 30.0, 200):
        o = sk.supine_at(*sk.at_arc(arc))
        ahead = sk.supine_at(*sk.at_arc(arc + 20.0))
        started = time.perf_counter()
        try:
            linker.link_camera(CameraPose(o, ahead, np.cross(ahead - o, [1.0, 0.0, 0.0])))
        except ValueError:
            continue  # an axis through a gap between segments: the viewer keeps the last prone pose
        times.append(1000.0 * (time.perf_counter() - started))
    times = np.array(times)
    print(f"one update: median {np.median(times):.2f} ms, p90 {np.percentile(times, 90):.2f} ms, "
          f"max {times.max():.2f} ms over {len(times)} poses")
    check(len(times) >= 150, f"only {len(times)} of 200 poses along the colon could be linked")
    check(np.median(times) <= 20.0 and np.percentile(times, 90) <= 20.0, "an update takes more than 20 ms")

    # Run folders.
    run = os.path.join(work, "run")
    os.makedirs(os.path.join(run, "transfer"))
    shutil.copy(registration, run)
    shutil.copy(findings, os.path.join(run, "transfer", "findings_prone.mrk.json"))
    json.dump({"inputs": {"supine": os.path.join(data, "phantom-2.5mm", "supine.nrrd"), "prone": "/nowhere/prone.nrrd",
                          "labelMaps": False, "findings": findings},
               "findings": [{"label": "P1", "supine": [1, 2, 3], "prone": [4, 5, 6], "segment": "S", "uncertaintyMm": 3.25,
                             "reliable": False}]}, open(os.path.join(run, "summary.json"), "w"))
    folder = RunFolder(run)
    check(folder.volumes["supine"] == os.path.join(data, "phantom-2.5mm", "supine.nrrd") and folder.volumes["prone"] is None,
          f"volumes: {folder.volumes}")
    check(folder.markups["findings_prone"] is not None and folder.markups["findings"] == os.path.abspath(findings), "markups")
    check(folder.findings() == [("P1", [1.0, 2.0, 3.0], [4.0, 5.0, 6.0], "uncertainty 3.2 mm, not reliable, segment S")],
          f"findings: {folder.findings()}")
    try:
        RunFolder(os.path.join(work, "views"))
        check(False, "a folder without registration.vtp was accepted")
    except ValueError as e:
        check("no registration.vtp" in str(e), str(e))
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
