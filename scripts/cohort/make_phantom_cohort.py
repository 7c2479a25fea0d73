#!/usr/bin/env python3
"""A phantom cohort for tests and demos of the cohort workflow (issue 25): N supine/prone pairs by
seed from ColonPhantom, each with its polyps as findings and its ground truth, and a case table.

    make_phantom_cohort.py --output DIR [--cases 3] [--first-seed 1] [--spacing 2.5,2.5,2.5]
                           [--real-colon DIR ...] [--no-colon N] [--cli DIR] [-- PHANTOM ARGS...]

Writes DIR/<case>/ (a ColonPhantom output folder per case: supine.nrrd, prone.nrrd, polyps, truth)
and DIR/cases.csv (case,supine,prone,findings,truth, paths relative to DIR). Case ids: phantom-s<seed>
for the tube phantom; with --real-colon, one more pair per real-colon folder (ColonPhantom
--realColon, docs/real-colon-phantom.md), id real-<folder name>-s<seed>. --no-colon N adds N broken
cases (no-colon-<k>): a uniform soft-tissue CT (40 HU, no air at all) for supine and prone, which
ColonSegmentation refuses ("no distended colon found"), to see a failing case reported. A pair that
already exists (its truth.json is there) is not made again.
"""
import argparse
import os
import struct
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_CLI = os.path.join(os.path.dirname(os.path.dirname(HERE)), "build", "ColonMap-build", "lib", "ColonMap",
                           "cli-modules")


def phantom(cli, folder, seed, spacing, real_colon, extra):
    if os.path.isfile(os.path.join(folder, "truth.json")):
        return
    cmd = [os.path.join(cli, "ColonPhantom"), "--outputDirectory", folder, "--seed", str(seed),
           "--spacing", spacing] + (["--realColon", real_colon] if real_colon else []) + extra
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"make_phantom_cohort: {' '.join(cmd)} failed: {r.stderr.strip()}")


def uniform_ct(path, size=(64, 64, 64), spacing=2.5, value=40):
    """A NRRD volume of one value (short, raw): a 'CT' with no air and so no colon."""
    if os.path.exists(path):
        return
    header = ("NRRD0004\n# ColonMap make_phantom_cohort.py: uniform soft tissue, no colon\n"
              "type: short\ndimension: 3\n"
              f"sizes: {size[0]} {size[1]} {size[2]}\n"
              f"space: left-posterior-superior\nspace directions: ({spacing},0,0) (0,{spacing},0) (0,0,{spacing})\n"
              "space origin: (0,0,0)\nendian: little\nencoding: raw\n\n")
    n = size[0] * size[1] * size[2]
    tmp = path + ".part"
    with open(tmp, "wb") as f:
        f.write(header.encode())
        f.write(struct.pack("<h", value) * n)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--output", required=True)
    ap.add_argument("--cases", type=int, default=3, help="tube phantom pairs (seeds first-seed, first-seed+1, ...)")
    ap.add_argument("--first-seed", type=int, default=1)
    ap.add_argument("--spacing", default="2.5,2.5,2.5", help="voxel size in mm (2.5: small and fast)")
    ap.add_argument("--real-colon", action="append", default=[], metavar="DIR",
                    help="also one real-colon pair per folder (e.g. ../shared/data/hubmap-vhf-00080)")
    ap.add_argument("--no-colon", type=int, default=0, metavar="N", help="add N broken cases without a colon")
    ap.add_argument("--cli", default=DEFAULT_CLI, help="the cli-modules folder")
    ap.add_argument("phantom_args", nargs=argparse.REMAINDER, help="after --: more ColonPhantom options")
    a = ap.parse_args()
    extra = a.phantom_args[1:] if a.phantom_args[:1] == ["--"] else a.phantom_args
    os.makedirs(a.output, exist_ok=True)
    rows = []
    for k in range(a.cases):
        seed = a.first_seed + k
        cid = f"phantom-s{seed}"
        phantom(a.cli, os.path.join(a.output, cid), seed, a.spacing, None, extra)
        rows.append((cid, f"{cid}/supine.nrrd", f"{cid}/prone.nrrd", f"{cid}/supine_polyps.mrk.json", cid))
    for j, real in enumerate(a.real_colon):
        seed = a.first_seed + j
        cid = f"real-{os.path.basename(os.path.normpath(real))}-s{seed}"
        phantom(a.cli, os.path.join(a.output, cid), seed, a.spacing, os.path.abspath(real), extra)
        rows.append((cid, f"{cid}/supine.nrrd", f"{cid}/prone.nrrd", f"{cid}/supine_polyps.mrk.json", cid))
    for k in range(1, a.no_colon + 1):
        cid = f"no-colon-{k}"
        os.makedirs(os.path.join(a.output, cid), exist_ok=True)
        uniform_ct(os.path.join(a.output, cid, "ct.nrrd"))
        rows.append((cid, f"{cid}/ct.nrrd", f"{cid}/ct.nrrd", "", ""))
    with open(os.path.join(a.output, "cases.csv"), "w") as f:
        f.write("case,supine,prone,findings,truth\n")
        for r in rows:
            f.write(",".join(r) + "\n")
    print(os.path.join(a.output, "cases.csv"))


if __name__ == "__main__":
    main()
