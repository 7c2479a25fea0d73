#!/usr/bin/env python3
"""The whole pipeline on a real-colon ground-truth pair (issue 17): ColonPhantom --realColon makes
a supine/prone CT pair of the HuBMAP female colon at 2 mm, ColonSupineProne runs every stage on
the two CTs, and the registration is measured against the exact truth: it must beat taking the
supine positions as prone ("no registration"), overall and in every segment.

Usage: real_colon_pipeline_test.py <cli-modules folder> <shared folder>
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
work = tempfile.mkdtemp(prefix="colonmap-real-pipeline-test-")
try:
    phantom, out = os.path.join(work, "phantom"), os.path.join(work, "out")
    r = run_program(os.path.join(cli, "ColonPhantom"), "--outputDirectory", phantom, "--seed", "3", "--spacing", "2,2,2",
                    "--realColon", os.path.join(shared, "data", "hubmap-vhf-00080"))
    check(r.returncode == 0, f"ColonPhantom failed: {r.stderr}")
    r = run_program(os.path.join(cli, "ColonSupineProne"), "--supine", os.path.join(phantom, "supine.nrrd"),
                    "--prone", os.path.join(phantom, "prone.nrrd"), "--outputDirectory", out,
                    "--groundTruth", phantom, "--findings", os.path.join(phantom, "supine_polyps.mrk.json"), "--skipViews")
    check(r.returncode == 0 and r.stderr == "", f"ColonSupineProne failed: {r.returncode} {r.stderr}")
    if r.returncode == 0:
        for name in ("registration.vtp", "summary.json", "report.html", "evaluation/errors.json",
                     "transfer/findings_prone.mrk.json"):
            check(os.path.exists(os.path.join(out, name)), f"missing {name}")
        errors = json.load(open(os.path.join(out, "evaluation", "errors.json")))
        truth = json.load(open(os.path.join(phantom, "truth.json")))
        mean, none = errors["overall"]["error3D"]["mean"], truth["noRegistration"]["mean"]
        print(f"real colon (HuBMAP VHF, seed 3, 2 mm): registration {mean:.2f} mm mean, no registration {none:.2f} mm")
        check(mean < 0.5 * none, f"registration {mean:.2f} mm is not clearly better than none ({none:.2f} mm)")
        for seg, e in errors["segments"].items():
            baseline = truth["segments"][seg]["noRegistration"]["mean"]
            print(f"  {seg}: {e['error3D']['mean']:.2f} mm (none {baseline:.2f})")
            check(e["error3D"]["mean"] < baseline, f"segment {seg}: {e['error3D']['mean']:.2f} mm, none {baseline:.2f} mm")
        findings = json.load(open(os.path.join(out, "transfer", "findings_prone.mrk.json")))["markups"][0]["controlPoints"]
        polyps = json.load(open(os.path.join(phantom, "supine_polyps.mrk.json")))["markups"][0]["controlPoints"]
        check(len(findings) == len(polyps), "every polyp carried to the prone scan")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
