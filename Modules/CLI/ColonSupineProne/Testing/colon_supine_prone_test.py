#!/usr/bin/env python3
"""ColonSupineProne as a user runs it (issue 9): the whole pipeline on the 2.5 mm phantom pair
with findings and the phantom's ground truth; the report is self-contained and carries the
flags, errors and stage times; ColonTransferPoints works on OUT/registration.vtp; label-map
inputs skip cleansing and segmentation; a rerun replaces the stage folders and keeps the user's
files; bad inputs fail with one line and leave nothing.

    colon_supine_prone_test.py CLI_DIR PHANTOM_DIR REAL_CT_DIR
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..",
                                "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

cli, phantom, real = sys.argv[1:4]
exe = os.path.join(cli, "ColonSupineProne")
t = Checks()
work = tempfile.mkdtemp(prefix="colonmap-supineprone-")
STAGES = ["cleansing", "segmentation", "surface", "landmarks", "flattening", "registration", "transfer",
          "evaluation"]


def pipeline(out, *extra, inputs=None):
    supine, prone = inputs or (os.path.join(phantom, "supine.nrrd"), os.path.join(phantom, "prone.nrrd"))
    ret = os.path.join(work, "ret.txt")
    r = run_program(exe, "--supine", supine, "--prone", prone, "--outputDirectory", out, "--targetFaces", "40000",
                    "--returnparameterfile", ret, *extra)
    return r, return_parameters(ret)


def no_output_left(folder):
    return not os.path.exists(folder) or not [n for n in os.listdir(folder)]


# 1. The whole pipeline with findings and ground truth.
out = os.path.join(work, "out")
r, ret = pipeline(out, "--findings", os.path.join(phantom, "supine_polyps.mrk.json"), "--groundTruth", phantom)
t.check(r.returncode == 0, f"pipeline exit {r.returncode}: {r.stderr.strip()}")
t.check(r.stderr == "", "stderr empty on success: " + r.stderr[:300])
for stage in STAGES:
    t.check(os.path.isdir(os.path.join(out, stage)), f"stage folder {stage}")
for f in ("registration.vtp", "registration_prone.vtp", "summary.json", "report.html",
          "landmarks/supine/segment_A.vtp", "flattening/prone/flat_R.vtp", "transfer/findings_prone.mrk.json"):
    t.check(os.path.isfile(os.path.join(out, f)), f"output {f}")
t.check(not [n for n in os.listdir(out) if n.startswith(".colonmap-tmp")], "no temporaries left")
summary = json.load(open(os.path.join(out, "summary.json"))) if os.path.exists(os.path.join(out, "summary.json")) else {}
names = [s["name"] for s in summary.get("stages", [])]
for stage in ("cleansing supine", "segmentation prone", "surface supine", "landmarks", "flattening supine",
              "registration", "transfer findings", "evaluation"):
    t.check(stage in names, f"summary.json has stage '{stage}'")
t.check(all(s["seconds"] > 0 for s in summary.get("stages", [])), "every stage has a time")
# CPU during each stage (issue 22). A stage run alone: the whole process's, positive and at most
# what the machine's cores could give in that wall time (a little slack for the clocks'
# granularity). A stage of a job run side by side with another (the two scans', the two views
# modules'): its own thread's, and its block has the process's.
cores = os.cpu_count() or 1
stages = summary.get("stages", [])
blocks = {b["name"]: b for b in summary.get("stageBlocks", [])}
alone = [s for s in stages if "block" not in s]
t.check(all(0 < s.get("cpuSeconds", 0) <= cores * s["seconds"] + 0.05 for s in alone),
        "every stage run alone has its CPU seconds, within cores x wall")
t.check(all(s["block"] in blocks and 0 < s.get("threadCpuSeconds", 0) <= s["seconds"] + 0.05
            for s in stages if "block" in s), "every stage of a scan's job has its thread's CPU seconds")
t.check(len(blocks) == 3 and all(b.get("sideBySide") is True and 0 < b["cpuSeconds"] <= cores * b["seconds"] + 0.05
                                 for b in blocks.values()), "three blocks (scans, flattenings, views), run side by side")
views = blocks.get("views: flat and endoluminal", {})
t.check(views.get("stages") == ["flat views", "endoluminal views"], f"the views block: {views.get('stages')}")
t.check(sorted(n for b in blocks.values() for n in b["stages"]) == sorted(s["name"] for s in stages if "block" in s),
        "each block lists its stages")
# Side by side, a block takes less than its stages one after the other (both cores at work).
scans = blocks.get("scans: cleansing, segmentation, surface", {})
t.check(scans and scans["seconds"] < sum(s["seconds"] for s in stages if s.get("block") == scans["name"]),
        "the scans' block took less than its stages in a row")
wall = sum(s["seconds"] for s in alone) + sum(b["seconds"] for b in blocks.values())
t.check(abs(wall - summary.get("totalSeconds", -1)) < 0.01, "totalSeconds: the stages run alone plus the blocks")
flags = summary.get("quality", [])
t.check(len(flags) >= 8 and all({"name", "ok", "detail"} <= set(f) for f in flags), "quality flags present")
t.check(summary.get("warnings") == sum(1 for f in flags if not f["ok"]), "warnings counts the flags not OK")
t.check(ret.get("warnings") == str(summary.get("warnings")), "return parameter warnings")
# The reported error is the evaluation's own, measured against the phantom's truth.
errors = json.load(open(os.path.join(out, "evaluation", "errors.json")))
mean = errors["overall"]["error3D"]["mean"]
t.check(abs(float(ret.get("meanError", "nan")) - mean) < 1e-3, "meanError return parameter = evaluation mean")
t.check(mean < 15.0, f"registration mean error {mean:.2f} mm on the 2.5 mm phantom")
# Each finding: mapped, its true error recomputed from the phantom's prone polyps.
truth = {p["label"]: p["position"] for p in json.load(open(os.path.join(phantom, "prone_polyps.mrk.json")))
         ["markups"][0]["controlPoints"]}
findings = summary.get("findings", [])
t.check(len(findings) == len(truth) and len(findings) > 0, f"{len(findings)} findings in the summary")
for f in findings:
    err = math.dist(f["prone"], truth[f["label"]])
    t.check(abs(err - f.get("trueErrorMm", -1)) < 1e-6, f"finding {f['label']} true error {err:.2f} mm")
    t.check(f.get("uncertaintyMm", 0) > 0, f"finding {f['label']} has an uncertainty")
# The report: one self-contained page.
html = open(os.path.join(out, "report.html")).read() if os.path.exists(os.path.join(out, "report.html")) else ""
srcs = re.findall(r'src="([^"]*)"', html)
t.check(all(s.startswith("data:image/png;base64,") for s in srcs), "every image is embedded")
t.check(not re.search(r'href="(?!#)', html), "no links to other files")
for f in flags:
    t.check(f["name"] in html.replace("&amp;", "&"), f"report shows flag '{f['name']}'")
t.check(f"{mean:.2f}" in html, "report shows the mean error")
t.check("Stage times" in html and "registration" in html, "report has the stage times")
if os.path.exists(os.path.join(cli, "ColonFlatViews")):
    t.check(len(srcs) >= 3, f"report embeds the flat views ({len(srcs)} images)")
    t.check(os.path.isfile(os.path.join(out, "flatviews", "flat_pair_registered.png")), "flat views written")

# 1b. One scan after the other (--sequential) gives the same files, byte for byte, as the two scans
# side by side (issue 22): only the times in summary.json and report.html differ.
outSeq = os.path.join(work, "out-sequential")
rs, _ = pipeline(outSeq, "--findings", os.path.join(phantom, "supine_polyps.mrk.json"), "--groundTruth", phantom,
                 "--sequential")
t.check(rs.returncode == 0, f"sequential run: {rs.stderr.strip()}")


def files(folder):
    return sorted(os.path.relpath(os.path.join(d, f), folder) for d, _, fs in os.walk(folder) for f in fs)


t.check(files(out) == files(outSeq), "side by side and one after the other write the same files")
timed = {"summary.json", "report.html"}
differ = [f for f in files(out) if f not in timed and os.path.exists(os.path.join(outSeq, f))
          and open(os.path.join(out, f), "rb").read() != open(os.path.join(outSeq, f), "rb").read()]
t.check(len(files(out)) > 40 and not differ, f"every output byte-identical ({len(files(out))} files; differ: {differ})")
sSeq = json.load(open(os.path.join(outSeq, "summary.json"))) if os.path.exists(os.path.join(outSeq, "summary.json")) else {}
t.check([b.get("sideBySide") for b in sSeq.get("stageBlocks", [])] == [False] * 3, "--sequential is recorded")

# 1c. No X display: the endoluminal views cannot render, the run stands and says why; the flat
# views are written without their 3D pictures.
outNoX = os.path.join(work, "out-no-display")
env = dict(os.environ)
env.pop("DISPLAY", None)
rn = subprocess.run([exe, "--supine", os.path.join(phantom, "supine.nrrd"), "--prone", os.path.join(phantom, "prone.nrrd"),
                     "--outputDirectory", outNoX, "--targetFaces", "40000", "--findings",
                     os.path.join(phantom, "supine_polyps.mrk.json")], capture_output=True, text=True,
                    stdin=subprocess.DEVNULL, env=env)
t.check(rn.returncode == 0, f"run without a display: exit {rn.returncode}: {rn.stderr.strip()[:300]}")
sNoX = json.load(open(os.path.join(outNoX, "summary.json"))) if os.path.exists(os.path.join(outNoX, "summary.json")) else {}
t.check(any(n.startswith("No endoluminal views:") and "display" in n for n in sNoX.get("notes", [])),
        f"without a display the notes say why there are no endoluminal views: {sNoX.get('notes')}")
t.check("endoluminal views" not in [s["name"] for s in sNoX.get("stages", [])] and
        "flat views" in [s["name"] for s in sNoX.get("stages", [])], "flat views made, no endoluminal views stage")
t.check(os.path.isfile(os.path.join(outNoX, "flatviews", "flat_pair_registered.png")) and
        not os.path.exists(os.path.join(outNoX, "flatviews", "distortion_3d.png")), "flat pictures without the 3D ones")

# 2. More findings through OUT/registration.vtp, as the README tells users to do.
mapped = os.path.join(work, "mapped.mrk.json")
r2 = run_program(os.path.join(cli, "ColonTransferPoints"), "--registration", os.path.join(out, "registration.vtp"),
                 "--input", os.path.join(phantom, "supine_eval.mrk.json"), "--output", mapped)
t.check(r2.returncode == 0 and os.path.exists(mapped), "ColonTransferPoints on OUT/registration.vtp: " + r2.stderr)

# 3. A rerun into the same folder replaces the stage folders and keeps the user's own files.
open(os.path.join(out, "cleansing", "stale.txt"), "w").write("old")
open(os.path.join(out, "my_notes.txt"), "w").write("mine")
r3, _ = pipeline(out, "--skipViews")
t.check(r3.returncode == 0, "rerun: " + r3.stderr)
t.check(not os.path.exists(os.path.join(out, "cleansing", "stale.txt")), "rerun replaced the stage folder")
t.check(os.path.exists(os.path.join(out, "my_notes.txt")), "rerun kept the user's file")

# 4. Label maps from another tool: no cleansing or segmentation, the rest as before.
labels = os.path.join(work, "labels")
os.makedirs(labels)
for scan in ("supine", "prone"):
    shutil.copy(os.path.join(out, "segmentation", f"{scan}_lumen.nrrd"), os.path.join(labels, f"{scan}.nrrd"))
out4 = os.path.join(work, "out-labels")
r4, _ = pipeline(out4, "--labelMaps", "--findings", os.path.join(phantom, "supine_polyps.mrk.json"),
                 inputs=(os.path.join(labels, "supine.nrrd"), os.path.join(labels, "prone.nrrd")))
t.check(r4.returncode == 0, "label maps: " + r4.stderr)
t.check(not os.path.exists(os.path.join(out4, "cleansing")) and not os.path.exists(os.path.join(out4, "segmentation")),
        "label maps: no cleansing or segmentation folders")
t.check(os.path.isfile(os.path.join(out4, "registration.vtp")), "label maps: registration written")
s4 = json.load(open(os.path.join(out4, "summary.json"))) if os.path.exists(os.path.join(out4, "summary.json")) else {}
t.check(any("label maps" in n for n in s4.get("notes", [])), "label maps: the report says why there are no views")
# The surfaces side by side and one after the other: the same files here too.
out4s = os.path.join(work, "out-labels-sequential")
r4s, _ = pipeline(out4s, "--labelMaps", "--findings", os.path.join(phantom, "supine_polyps.mrk.json"), "--sequential",
                  inputs=(os.path.join(labels, "supine.nrrd"), os.path.join(labels, "prone.nrrd")))
t.check(r4s.returncode == 0, "label maps, sequential: " + r4s.stderr)
differ4 = [f for f in files(out4) if f not in timed and (not os.path.exists(os.path.join(out4s, f)) or
           open(os.path.join(out4, f), "rb").read() != open(os.path.join(out4s, f), "rb").read())]
t.check(files(out4) == files(out4s) and not differ4, f"label maps: side by side = sequential, byte for byte ({differ4})")
t.check([b.get("name") for b in s4.get("stageBlocks", [])][:1] == ["scans: surface"], "label maps: the block is the surfaces'")

# 5. Bad inputs: one line on stderr naming the input, non-zero exit, nothing left.
cases = [
    ("missing supine", (os.path.join(work, "nope.nrrd"), os.path.join(phantom, "prone.nrrd")), [], "supine scan"),
    ("no colon in the scan", (os.path.join(real, "example_ct.nii.gz"), os.path.join(phantom, "prone.nrrd")), [],
     "ColonSegmentation"),
    ("bad ground truth", None, ["--groundTruth", work], "ground truth folder"),
]
for name, inputs, extra, expected in cases:
    bad = os.path.join(work, "bad-" + name.replace(" ", "-"))
    rb, _ = pipeline(bad, *extra, inputs=inputs)
    lines = rb.stderr.strip().splitlines()
    t.check(rb.returncode != 0, f"{name}: non-zero exit")
    t.check(len(lines) == 1 and expected in rb.stderr, f"{name}: one stderr line naming '{expected}': {rb.stderr!r}")
    t.check(no_output_left(bad), f"{name}: nothing left in the output folder")

shutil.rmtree(work, ignore_errors=True)
sys.exit(t.finish())
