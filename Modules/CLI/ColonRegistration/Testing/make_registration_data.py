#!/usr/bin/env python3
"""Test data of the registration modules: <out>/{supine,prone}-landmarks (true wall, true-centreline
arc length), <out>/{supine,prone}_{eval,polyps}.mrk.json, <out>/{supine,prone} (ColonFlattening),
<out>/registration (ColonRegistration, conformal) and <out>/registration-centerline (the centerline
arc-length baseline).

Usage: make_registration_data.py <MakeTestData> <ColonFlattening> <ColonRegistration> <out> <step> <around> <seed>
"""
import os
import shutil
import subprocess
import sys

make, flatten, register, out, step, around, seed = sys.argv[1:8]
if os.path.isdir(out):
    shutil.rmtree(out)
raw = os.path.join(out, "landmarks")


def run(*args):
    r = subprocess.run(list(args), capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{args[0]} failed ({r.returncode}): {r.stderr}")
    return r


run(make, raw, step, around, seed)
for scan in ("supine", "prone"):
    run(flatten, os.path.join(raw, scan), os.path.join(out, scan))
    for kind in ("eval", "polyps"):
        shutil.copy(os.path.join(raw, f"{scan}_{kind}.mrk.json"), os.path.join(out, f"{scan}_{kind}.mrk.json"))
run(register, "--method", "conformal", os.path.join(out, "supine"), os.path.join(out, "prone"),
    os.path.join(out, "registration"))
run(register, "--method", "centerline", os.path.join(out, "supine"), os.path.join(out, "prone"),
    os.path.join(out, "registration-centerline"))
print("registration test data in", out)
