#!/usr/bin/env python3
"""The whole pipeline on colons with collapsed stretches (issue 21), against the exact truth:
ColonPhantom --collapse makes a pair whose lumen is closed over stretches of one scan or both (the
tube phantom at 2.5 mm, seeds 4 and 9, and the HuBMAP male colon at 2 mm), ColonSupineProne runs every stage on
the two CTs. Checked: the run completes; each scan's segmentation keeps one piece more than its
collapses; the wall open in both scans registers within 3 mm on average (3.5 mm on the real
colon); every evaluation point open in the supine scan but collapsed in the prone one is marked
visible=false, and nearly every one inside a supine collapse; few open points are; the report
flags the collapse.

Usage: collapsed_colon_test.py <cli-modules folder> <shared folder>
"""
import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, run_program  # noqa: E402

cli, shared = sys.argv[1], sys.argv[2]
checks = Checks()
check = checks.check
work = tempfile.mkdtemp(prefix="colonmap-collapsed-test-")
# (name, ColonPhantom options, largest mean error on the wall open in both scans): a tube whose
# prone sigmoid is collapsed (seed 4), and a real colon with one stretch collapsed in each scan
# (seed 1). Tube seed 9 with two collapses: a cut taenia one taenia off in segment A of one
# scan, and a sliver in its flat map that once vetoed the curvature warp that corrects it
# (12.9 mm mean). 3 mm on the tube (measured 2.32, 2.36 mm); 3.5 mm on the real colon at 2 mm,
# whose pairs scatter more from sample to sample (VHM seed 1: 3.03 mm since the atlas weld is the
# same on every run, 2.55-2.67 on the weld's earlier run-to-run variants; at 1 mm with 2
# collapses GCA 3.06 and 2.63, docs/accuracy.md).
cases = [("tube seed 4, 1 collapse", ["--seed", "4", "--spacing", "2.5,2.5,2.5", "--collapse", "1"], 3.0),
         ("tube seed 9, 2 collapses", ["--seed", "9", "--spacing", "2.5,2.5,2.5", "--collapse", "2"], 3.0),
         ("HuBMAP VHM seed 1, 2 collapses", ["--seed", "1", "--spacing", "2,2,2", "--collapse", "2",
                                              "--realColon", os.path.join(shared, "data", "hubmap-vhm-00070")], 3.5)]
try:
    for k, (name, options, openLimit) in enumerate(cases):
        phantom, out = os.path.join(work, f"phantom{k}"), os.path.join(work, f"out{k}")
        r = run_program(os.path.join(cli, "ColonPhantom"), "--outputDirectory", phantom, *options)
        check(r.returncode == 0, f"{name}: ColonPhantom failed: {r.stderr}")
        if r.returncode:
            continue
        truth = json.load(open(os.path.join(phantom, "truth.json")))
        r = run_program(os.path.join(cli, "ColonSupineProne"), "--supine", os.path.join(phantom, "supine.nrrd"),
                        "--prone", os.path.join(phantom, "prone.nrrd"), "--outputDirectory", out,
                        "--groundTruth", phantom, "--findings", os.path.join(phantom, "supine_polyps.mrk.json"),
                        "--skipViews")
        check(r.returncode == 0 and r.stderr == "", f"{name}: ColonSupineProne failed: {r.returncode} {r.stderr}")
        if r.returncode:
            continue
        summary = json.load(open(os.path.join(out, "summary.json")))
        stages = {s["name"]: s for s in summary["stages"]}
        for scan in ("supine", "prone"):
            closed = sum(scan in c["scans"] for c in truth["collapses"])
            kept = int(stages["segmentation " + scan]["results"]["componentsKept"])
            print(f"{name}: {scan}: {closed} collapsed stretch(es), {kept} piece(s)")
            check(kept == closed + 1, f"{name}: {scan}: {kept} pieces kept, the truth has {closed} collapses")
        errors = json.load(open(os.path.join(out, "evaluation", "errors.json")))
        c = errors["collapsed"]
        openMean = errors["open"]["error3D"]["mean"]
        openCount = errors["open"]["error3D"]["count"]
        print(f"{name}: open in both scans {openCount} points, mean {openMean:.2f} mm; collapsed in prone only "
              f"{c['proneOnly']}, marked visible=false {c['proneOnlyNotVisible']}; open points marked {c['openButNotVisible']}")
        check(openMean <= openLimit, f"{name}: wall open in both scans {openMean:.2f} mm mean (> {openLimit} mm)")
        check(c["proneOnlyNotVisible"] == c["proneOnly"], f"{name}: a point on collapsed prone wall was given a position")
        check(c["openButNotVisible"] <= 0.05 * openCount, f"{name}: {c['openButNotVisible']} open points marked not visible")
        # Points inside a supine collapse (no reader can mark one, but a position there would be
        # false): marked too, save those within 3 mm of the seen wall at a collapse's end (1 of 17
        # on seed 9, at 1.9 mm; 140 of 143 over 20 tube pairs, docs/accuracy.md): at most 10% of
        # them, and one where there are fewer than 10. HuBMAP VHM has 7: 6 marked (7 on some of
        # the weld's earlier run-to-run variants).
        print(f"{name}: collapsed in supine {c['supine']}, marked visible=false {c['supineNotVisible']}")
        check(c["supine"] - c["supineNotVisible"] <= max(1, int(0.1 * c["supine"])),
              f"{name}: {c['supineNotVisible']} of {c['supine']} points in supine-collapsed wall marked visible=false")
        flags = {f["name"]: f for f in summary["quality"]}
        pieces = summary.get("pieces", {})
        for scan in ("supine", "prone"):
            closed = sum(scan in c["scans"] for c in truth["collapses"])
            got = pieces.get(scan, {}).get("pieces")
            check(got == closed + 1, f"{name}: summary.json pieces of {scan}: {got}, the truth has {closed} collapses")
        report = open(os.path.join(out, "report.html")).read()
        check("Colon pieces and collapsed stretches" in report, f"{name}: the report has no section on the pieces")
        check("Colon open in both scans" in flags and not flags["Colon open in both scans"]["ok"],
              f"{name}: the report does not flag the collapse")
        # Findings: those on prone-collapsed wall say so; every finding is carried.
        mapped = json.load(open(os.path.join(out, "transfer", "findings_prone.mrk.json")))["markups"][0]["controlPoints"]
        prone = {p["label"]: p for p in json.load(open(os.path.join(phantom, "prone_polyps.mrk.json")))["markups"][0]["controlPoints"]}
        table = {row["label"]: row for row in summary["findings"]}
        for p in mapped:
            if "collapsed=true" in prone[p["label"]]["description"]:
                check("visible=false" in p["description"], f"{name}: polyp {p['label']} on collapsed prone wall: {p['description']}")
                check(table[p["label"]].get("visible") is False, f"{name}: polyp {p['label']}: summary.json does not say so")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
