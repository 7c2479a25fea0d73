#!/usr/bin/env python3
"""The main job on the built-in default input, with the stages that exist today: a phantom
supine/prone pair, then per scan cleansing, lumen segmentation, surface reconstruction,
landmarks and conformal flattening, then the registration (conformal-map baseline: no features
yet), the phantom's polyps carried from supine to prone, and the registration error against the
phantom's ground truth.
Each stage's outputs go to a subfolder of OUT named after the stage (DESIGN section 2.0);
OUT/summary.json holds stage times, each module's return parameters and what is not built yet.

    demo_pipeline.py --cli-dir DIR --output OUT [ColonPhantom options...]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

NOT_YET = ["features and matching (harmonic registration)", "views", "report"]


def run_stage(cli, module, args, summary, key):
    exe = os.path.join(cli, module)
    if not os.path.exists(exe):
        return False
    with tempfile.NamedTemporaryFile("r", suffix=".txt") as ret:
        start = time.time()
        r = subprocess.run([exe, "--returnparameterfile", ret.name] + args, text=True,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        seconds = time.time() - start
        for line in r.stdout.splitlines():  # the module's notes, without Slicer's progress tags
            if not line.startswith("<filter"):
                print(line)
        if r.returncode != 0:
            sys.stderr.write(r.stderr)
            raise SystemExit(f"ColonMap demo: {module} failed; outputs so far are in the output folder")
        values = dict(re.findall(r"^(\w+) = (.*)$", open(ret.name).read(), re.M))
    summary["stages"][key] = {"seconds": round(seconds, 2), "module": module, "results": values}
    print(f"ColonMap demo: {key} done in {seconds:.1f} s")
    return True


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cli-dir", required=True)
    parser.add_argument("--output", required=True)
    args, phantom_options = parser.parse_known_args()
    out, cli = os.path.abspath(args.output), args.cli_dir
    os.makedirs(out, exist_ok=True)
    summary = {"input": "ColonPhantom " + " ".join(phantom_options), "stages": {}, "notYetAvailable": NOT_YET}
    run_stage(cli, "ColonPhantom", ["--outputDirectory", os.path.join(out, "phantom")] + phantom_options,
              summary, "phantom")
    for folder in ("cleansing", "segmentation", "surface", "landmarks", "flattening", "registration"):
        os.makedirs(os.path.join(out, folder), exist_ok=True)
    for scan in ("supine", "prone"):
        ct = os.path.join(out, "phantom", f"{scan}.nrrd")
        cleansed = os.path.join(out, "cleansing", f"{scan}_cleansed.nrrd")
        lumen = os.path.join(out, "segmentation", f"{scan}_lumen.nrrd")
        surface = os.path.join(out, "surface", f"{scan}_surface.vtp")
        if not run_stage(cli, "ColonCleansing", [ct, cleansed, "--taggedLabel",
                                                 os.path.join(out, "cleansing", f"{scan}_tagged.nrrd")],
                         summary, f"cleansing {scan}"):
            break
        if not run_stage(cli, "ColonSegmentation", [cleansed, lumen], summary, f"segmentation {scan}"):
            break
        if not run_stage(cli, "ColonSurface", [lumen, surface, "--referenceCT", cleansed], summary,
                         f"surface {scan}"):
            break
        landmarks = os.path.join(out, "landmarks", scan)
        if not run_stage(cli, "ColonLandmarks", [surface, landmarks], summary, f"landmarks {scan}"):
            break
        run_stage(cli, "ColonFlattening", [landmarks, os.path.join(out, "flattening", scan)], summary,
                  f"flattening {scan}")
    flat = os.path.join(out, "flattening")
    reg = os.path.join(out, "registration")
    phantom = os.path.join(out, "phantom")
    if os.path.exists(os.path.join(flat, "prone", "flattening.json")) and \
            run_stage(cli, "ColonRegistration", [os.path.join(flat, "supine"), os.path.join(flat, "prone"), reg],
                      summary, "registration"):
        run_stage(cli, "ColonTransferPoints",
                  ["--registration", os.path.join(reg, "registration.vtp"),
                   "--input", os.path.join(phantom, "supine_polyps.mrk.json"),
                   "--output", os.path.join(reg, "prone_polyps_mapped.mrk.json")], summary, "transfer polyps")
        if run_stage(cli, "ColonEvaluateRegistration",
                     ["--registration", os.path.join(reg, "registration.vtp"),
                      "--truthSupine", os.path.join(phantom, "supine_eval.mrk.json"),
                      "--truthProne", os.path.join(phantom, "prone_eval.mrk.json"),
                      "--polypsSupine", os.path.join(phantom, "supine_polyps.mrk.json"),
                      "--polypsProne", os.path.join(phantom, "prone_polyps.mrk.json"),
                      "--output", os.path.join(reg, "errors.json"),
                      "--outputTable", os.path.join(reg, "errors.tsv")], summary, "evaluation"):
            res = summary["stages"]["evaluation"]["results"]
            print("ColonMap demo: registration error on the phantom's evaluation points: mean "
                  f"{res.get('meanError')} mm, median {res.get('medianError')} mm, p90 {res.get('p90Error')} mm "
                  "(conformal map only, no feature matching yet)")
    summary["totalSeconds"] = round(sum(s["seconds"] for s in summary["stages"].values()), 2)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
    print(f"ColonMap demo: outputs in {out}, stage times in {os.path.join(out, 'summary.json')}")
    print("ColonMap demo: not built yet: " + ", ".join(summary["notYetAvailable"]) + " (README, Status)")


if __name__ == "__main__":
    main()
