#!/usr/bin/env python3
"""ColonLandmarks as a user runs it: outputs of the file contract, flexures against the phantom
truth, determinism, errors (missing file, open surface, several components, too small).

Usage: colon_landmarks_test.py <ColonLandmarks executable> <folder with {supine,prone}_surface.vtp
       and the phantom truth>
"""
import filecmp
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 4, "Testing", "Python"))
from colonmap_testing import Checks, return_parameters, run_program  # noqa: E402

exe, data = sys.argv[1], sys.argv[2]
checks = Checks()
check = checks.check
SCHEMA = os.path.join(os.path.dirname(__file__), "..", "..", "..", "..", "..", "shared", "schemas",
                      "markups-schema-v1.0.3.json")


def run(*args):
    return run_program(exe, *args)


returns = return_parameters


def vtp_header(path):
    raw = open(path, "rb").read()
    return raw[:raw.find(b"<AppendedData")].decode("utf-8", "replace")


def points(path):
    m = json.load(open(path))["markups"][0]
    return m, [(c["label"], c["position"], c.get("description", "")) for c in m["controlPoints"]]


def expected(label, tp, tf, line):
    """The truth for a flexure. DSJ: the bottom of the descent (the atlases' convention, as the DSJ
    rule follows it), the lowest truth-centreline point between the true SF and RSJ; the phantom's
    own DSJ, where its fixed descending colon meets the mobile sigmoid, lies 60-80 mm above."""
    if label != "DSJ":
        return tp
    pos = {f[0]: f[1] for f in tf}
    a, b = sorted((project(pos["SF"], line), project(pos["RSJ"], line)))
    arcs = [0.0]
    for q0, q1 in zip(line, line[1:]):
        arcs.append(arcs[-1] + math.dist(q0, q1))
    inside = [q for q, t in zip(line, arcs) if a < t < b]
    return min(inside, key=lambda q: q[2]) if inside else tp


def project(p, line):
    """Arc length of the nearest point on a polyline (list of 3D points)."""
    best, arc, acc = float("inf"), 0.0, 0.0
    for a, b in zip(line, line[1:]):
        d = [b[i] - a[i] for i in range(3)]
        L2 = sum(x * x for x in d)
        t = 0.0 if L2 == 0 else max(0.0, min(1.0, sum((p[i] - a[i]) * d[i] for i in range(3)) / L2))
        q = [a[i] + t * d[i] for i in range(3)]
        dist = math.dist(p, q)
        if dist < best:
            best, arc = dist, acc + t * math.sqrt(L2)
        acc += math.sqrt(L2)
    return arc


def stl(path, tetrahedra):
    with open(path, "w") as f:
        f.write("solid t\n")
        for ox in tetrahedra:
            v = [(ox, 0, 0), (ox + 10, 0, 0), (ox, 10, 0), (ox, 0, 10)]
            for tri in ((0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)):
                f.write(" facet normal 0 0 0\n  outer loop\n")
                for k in tri:
                    f.write("   vertex %g %g %g\n" % v[k])
                f.write("  endloop\n endfacet\n")
        f.write("endsolid t\n")


names = ["colon_open.vtp", "centerline.mrk.json", "flexures.mrk.json", "segment_A.vtp", "segment_T.vtp",
         "segment_D.vtp", "segment_S.vtp", "segment_R.vtp", "taeniae.vtp", "landmarks.json"]
work = tempfile.mkdtemp(prefix="colonmap-landmarks-test-")
try:
    for posture in ("supine", "prone"):
        surface = os.path.join(data, posture + "_surface.vtp")
        out = os.path.join(work, posture)
        ret = os.path.join(work, posture + "_ret.txt")
        r = run("--returnparameterfile", ret, surface, out)
        check(r.returncode == 0 and r.stderr == "", f"{posture} run: {r.returncode} {r.stderr}")
        check("<filter-end>" in r.stdout and "ColonLandmarks: centreline" in r.stdout, f"{posture} progress/notes")
        for n in names:
            check(os.path.isfile(os.path.join(out, n)), f"{posture}: {n} missing")
        if not os.path.isfile(os.path.join(out, "landmarks.json")):
            continue
        summary = json.load(open(os.path.join(out, "landmarks.json")))
        check(set(summary["segments"]) == set("ATDSR") and set(summary["flexures"]) == {"HF", "SF", "DSJ", "RSJ"},
              f"{posture}: landmarks.json keys")
        check("times" in summary and summary["segments"]["A"].get("cutTaenia") == "TO", f"{posture}: summary fields")
        v = returns(ret)
        check(abs(float(v["centerlineLength"]) - summary["centerlineLengthMm"]) < 0.1, "return centerlineLength")
        # Markups: valid against Slicer's schema, Curve from the anal end, flexure labels.
        try:
            import jsonschema
            schema = json.load(open(SCHEMA))
            for n in ("centerline.mrk.json", "flexures.mrk.json"):
                jsonschema.validate(json.load(open(os.path.join(out, n))), schema)
            check(True, "")
        except ImportError:
            pass
        except Exception as e:  # noqa: BLE001
            check(False, f"{posture}: markups schema: {e}")
        cm, cl = points(os.path.join(out, "centerline.mrk.json"))
        fm, fl = points(os.path.join(out, "flexures.mrk.json"))
        check(cm["type"] == "Curve" and fm["type"] == "Fiducial", "markups types")
        check([f[0] for f in fl] == ["HF", "SF", "DSJ", "RSJ"], f"flexure labels {[f[0] for f in fl]}")
        check(all(re.fullmatch(r"arcLength=[0-9.]+", f[2]) for f in fl), "flexure descriptions")
        # Against the truth: the truth centreline runs from the cecum to the anus.
        _, tc = points(os.path.join(data, posture + "_centerline.mrk.json"))
        _, tf = points(os.path.join(data, posture + "_flexures.mrk.json"))
        truth_line = [p[1] for p in tc]
        check(project(cl[0][1], truth_line) > project(cl[-1][1], truth_line), f"{posture}: centreline not from the anus")
        for (label, p, _), (tlabel, tp, _) in zip(fl, tf):
            d = project(p, truth_line) - project(expected(label, tp, tf, truth_line), truth_line)
            print(f"{posture} {label}: {d:+.1f} mm along the true centreline")
            check(label == tlabel and abs(d) < 20.0, f"{posture} {label} off by {d:.1f} mm")
        # Segment meshes and the opened colon carry the contract arrays.
        for n in ("colon_open.vtp", "segment_A.vtp", "segment_R.vtp"):
            h = vtp_header(os.path.join(out, n))
            check('Name="SegmentId"' in h and 'Name="CenterlineArcLength"' in h, f"{n}: arrays")
        h = vtp_header(os.path.join(out, "taeniae.vtp"))
        for a in ("Name", "SegmentId", "IsCut", "Confidence", "VertexId"):
            check(f'Name="{a}"' in h, f"taeniae.vtp: no {a} array")
        m = re.search(r'NumberOfLines="(\d+)"', h)
        check(m is not None and m.group(1) == "15", f"taeniae.vtp lines {m and m.group(1)}")

    # Same input, same bytes.
    again = os.path.join(work, "again")
    r = run(os.path.join(data, "supine_surface.vtp"), again)
    check(r.returncode == 0 and all(filecmp.cmp(os.path.join(work, "supine", n), os.path.join(again, n), shallow=False)
                                    for n in names), "two runs differ")

    # Both scans at once (--pairedSurface): each folder as a single run writes it, each flexure
    # within 20 mm of the truth in both scans, the joint choice in landmarks.json and the notes.
    ps, pp, ret = os.path.join(work, "pair_supine"), os.path.join(work, "pair_prone"), os.path.join(work, "pair_ret.txt")
    r = run("--returnparameterfile", ret, os.path.join(data, "supine_surface.vtp"), ps,
            "--pairedSurface", os.path.join(data, "prone_surface.vtp"), "--pairedOutputDirectory", pp)
    check(r.returncode == 0 and r.stderr == "", f"paired run: {r.returncode} {r.stderr}")
    check("ColonLandmarks: supine centreline" in r.stdout and "ColonLandmarks: prone centreline" in r.stdout and
          "joint with prone" in r.stdout, "paired notes")
    for posture, folder in (("supine", ps), ("prone", pp)):
        for n in names:
            check(os.path.isfile(os.path.join(folder, n)), f"paired {posture}: {n} missing")
        if not os.path.isfile(os.path.join(folder, "landmarks.json")):
            continue
        joint = json.load(open(os.path.join(folder, "landmarks.json"))).get("jointChoice", {})
        check(joint.get("pairedWith") == ("prone" if posture == "supine" else "supine") and joint.get("consistent"),
              f"paired {posture}: jointChoice {joint}")
        check(set(joint.get("flexures", {})) == {"HF", "SF", "DSJ", "RSJ"} and
              all(f["choice"] in ("agreed", "rechosen") or f["choice"].startswith("carried from ")
                  for f in joint.get("flexures", {}).values()), f"paired {posture}: choices")
        _, tc = points(os.path.join(data, posture + "_centerline.mrk.json"))
        _, tf = points(os.path.join(data, posture + "_flexures.mrk.json"))
        _, fl = points(os.path.join(folder, "flexures.mrk.json"))
        line = [q[1] for q in tc]
        for (label, p, _), (_, tp, _) in zip(fl, tf):
            d = project(p, line) - project(expected(label, tp, tf, line), line)
            check(abs(d) < 20.0, f"paired {posture} {label} off by {d:.1f} mm")
    v = returns(ret)
    check(v.get("pairedFlexureArcLengths", "").count(",") == 3, f"paired return parameters {v}")

    # Errors: one stderr line naming the input, non-zero exit, no output.
    two, one = os.path.join(work, "two.stl"), os.path.join(work, "one.stl")
    stl(two, [0, 100])
    stl(one, [0])
    for args, needle in (([os.path.join(work, "missing.vtp")], "missing.vtp"),
                         ([os.path.join(work, "supine", "segment_A.vtp")], "boundary loop"),
                         ([two], "2 component"),
                         ([one], "too few")):
        bad = os.path.join(work, "bad")
        r = run(*args, bad)
        check(r.returncode != 0, f"{args}: exit code 0")
        check(r.stderr.count("\n") == 1 and needle in r.stderr, f"{args}: stderr {r.stderr!r}")
        check(not os.path.exists(bad) or not os.listdir(bad), f"{args}: output written")
    # A bad paired surface is named as such (its file, "paired surface"); neither folder is written.
    bs, bp = os.path.join(work, "bad_s"), os.path.join(work, "bad_p")
    r = run(os.path.join(data, "supine_surface.vtp"), bs, "--pairedSurface", two, "--pairedOutputDirectory", bp)
    check(r.returncode != 0 and r.stderr.count("\n") == 1 and "paired surface" in r.stderr and "two.stl" in r.stderr,
          f"bad paired surface: {r.returncode} {r.stderr!r}")
    check(all(not os.path.exists(d) or not os.listdir(d) for d in (bs, bp)), "bad paired surface: output written")
    # Both scans into one folder would overwrite each other: refused.
    r = run(os.path.join(data, "supine_surface.vtp"), bs, "--pairedSurface", os.path.join(data, "prone_surface.vtp"),
            "--pairedOutputDirectory", bs + "/")
    check(r.returncode != 0 and r.stderr.count("\n") == 1 and "same folder" in r.stderr,
          f"same output folders: {r.returncode} {r.stderr!r}")
    check(not os.path.exists(bs) or not os.listdir(bs), "same output folders: output written")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
