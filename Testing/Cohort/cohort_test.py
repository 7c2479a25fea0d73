#!/usr/bin/env python3
"""Tests of the cohort workflow (issue 25): scripts/run-cohort.sh over a phantom cohort.

    cohort_test.py local|resume|slurm|report-only --repo REPO --cli CLI_DIR --data COHORT_DIR --work DIR

COHORT_DIR is made by scripts/cohort/make_phantom_cohort.py (fixture Cohort.MakePhantoms): two
2.5 mm phantom pairs (phantom-s1, phantom-s2) with findings and truth, and no-colon-1, a uniform
CT without air that ColonSegmentation refuses.
  local        the 3-case cohort on this machine within 2 min: the two phantom cases complete in
               ColonSupineProne's layout, the broken case fails alone and is reported with its
               module's stderr line; a rerun runs only the failed stages; a changed findings file
               reruns only that case's transfer, endoluminal views and report.
  resume       one case killed (SIGKILL of the whole run) while its landmarks stage runs, then run
               again: exactly the unfinished stages run, the finished ones are untouched.
  slurm        the same 3-case cohort through a single-node Slurm cluster started here
               (scripts/cohort/slurm_local.py) and stopped at the end, whatever happens.
  report-only  ColonSupineProne --reportOnly on a whole-pipeline output (its summary.json and
               report.html removed) writes them again byte for byte.
"""
import argparse
import csv
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

GOOD = ("phantom-s1", "phantom-s2")
BROKEN = "no-colon-1"
STAGES = ["cleansing supine", "segmentation supine", "surface supine", "cleansing prone", "segmentation prone",
          "surface prone", "landmarks", "flattening supine", "flattening prone", "registration", "flat views",
          "transfer findings", "endoluminal views", "evaluation"]
LAYOUT = ["registration.vtp", "registration_prone.vtp", "summary.json", "report.html",
          "cleansing/supine_cleansed.nrrd", "cleansing/prone_tagged.nrrd", "segmentation/supine_lumen.nrrd",
          "segmentation/prone_lumen.nrrd", "surface/supine_surface.vtp", "surface/prone_surface.vtp",
          "landmarks/supine/landmarks.json", "landmarks/prone/segment_R.vtp", "landmarks/prone/flexures.mrk.json",
          "flattening/supine/flattening.json", "flattening/prone/flat_A.vtp", "registration/registration.json",
          "registration/registration.vtp", "flatviews/flat_pair_registered.png", "transfer/findings_prone.mrk.json",
          "views/cameras.json", "views/view_P1.png", "evaluation/errors.json", "evaluation/errors.tsv"]

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)
    return ok


def finish(work=None):
    """Exits with the failed checks; on success removes the test's work folder (0.1-0.4 GB each)."""
    if failures:
        sys.exit(f"{len(failures)} check(s) failed (outputs kept in {work}):\n  " + "\n  ".join(failures))
    if work:
        shutil.rmtree(work, ignore_errors=True)
    print("all checks passed")


def write_table(path, cases, data, findings_override=None):
    """A case table in the work folder pointing into the fixture data (paths relative to the table)."""
    with open(path, "w") as f:
        f.write("case,supine,prone,findings,truth\n")
        for c in cases:
            rel = lambda p: os.path.relpath(os.path.join(data, p), os.path.dirname(path))
            if c == BROKEN:
                f.write(f"{c},{rel(c + '/ct.nrrd')},{rel(c + '/ct.nrrd')},,\n")
            else:
                findings = (findings_override or {}).get(c) or os.path.join(data, c, "supine_polyps.mrk.json")
                f.write(f"{c},{rel(c + '/supine.nrrd')},{rel(c + '/prone.nrrd')},"
                        f"{os.path.relpath(findings, os.path.dirname(path))},{rel(c)}\n")


def term_with_parent():
    """In the child before exec: SIGTERM when this test dies, however it ends (PR_SET_PDEATHSIG);
    run-cohort.sh then stops its Snakemake run."""
    import ctypes
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)


def run_cohort(a, table, out, *extra, env=None, timeout=600, prefix=()):
    """run-cohort.sh (after prefix) in a process group of its own; past the timeout the whole group
    is stopped."""
    cmd = [*prefix, "bash", os.path.join(a.repo, "scripts", "run-cohort.sh"), table, out, "--cli", a.cli, *extra]
    start = time.time()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                         start_new_session=True, preexec_fn=term_with_parent)
    try:
        stdout, stderr = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGTERM)
        try:
            stdout, stderr = p.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            stdout, stderr = p.communicate()
        stderr += f"\n(stopped after {timeout} s)"
    seconds = time.time() - start
    r = subprocess.CompletedProcess(cmd, p.returncode, stdout, stderr)
    print(f"$ {' '.join(cmd)}  ({seconds:.1f} s, exit {r.returncode})\n{r.stdout}{r.stderr}", flush=True)
    return r, seconds


def journal(out):
    rows = []
    try:
        with open(os.path.join(out, ".cohort", "journal.tsv")) as f:
            for line in f:
                t, case, stage, event = line.rstrip("\n").split("\t")[:4]
                rows.append((float(t), case, stage, event))
    except OSError:
        pass
    return rows


def started(rows):
    return sorted((case, stage) for _t, case, stage, event in rows if event == "start")


def module_error_line(stderr_path, module):
    with open(stderr_path, errors="replace") as f:
        lines = [l.strip() for l in f if l.strip().startswith(module + ": error: ")]
    return lines[-1] if lines else None


def check_good_case(out, case):
    d = os.path.join(out, case)
    missing = [p for p in LAYOUT if not os.path.isfile(os.path.join(d, p))]
    check(not missing, f"{case}: ColonSupineProne's layout complete (missing: {missing})")
    extra = [n for n in os.listdir(d) if n not in {p.split("/")[0] for p in LAYOUT} | {"logs", "flatviews", "views"}]
    check(not extra, f"{case}: nothing else in the case folder but logs/ ({extra})")
    try:
        s = json.load(open(os.path.join(d, "summary.json")))
    except (OSError, ValueError) as e:
        check(False, f"{case}: summary.json readable ({e})")
        return
    names = [st["name"] for st in s.get("stages", [])]
    check(names == STAGES, f"{case}: summary.json lists the stages in pipeline order ({names})")
    check(all(st.get("seconds", 0) > 0 and st.get("results") for st in s["stages"]),
          f"{case}: every stage has its seconds and its module's return parameters")
    check(len(s.get("quality", [])) >= 8, f"{case}: quality flags computed ({len(s.get('quality', []))})")
    check(len(s.get("findings", [])) >= 1 and all("trueErrorMm" in f for f in s["findings"]),
          f"{case}: findings table with the true error from the phantom truth")
    html = open(os.path.join(d, "report.html")).read()
    check("Linked endoluminal views" in html and html.count("data:image/png;base64") >= 8,
          f"{case}: report.html with the linked views and embedded pictures")


def check_broken_case(out, row):
    d = os.path.join(out, BROKEN)
    line = module_error_line(os.path.join(d, "logs", "segmentation_supine.stderr"), "ColonSegmentation")
    check(line is not None and "no distended colon found" in line,
          f"{BROKEN}: ColonSegmentation's own error on its stderr ({line})")
    check(row.get("status") == "failed" and row.get("failed_stage") == "segmentation supine",
          f"{BROKEN}: reported failed at 'segmentation supine' ({row.get('status')}, {row.get('failed_stage')})")
    check(row.get("reason") == line, f"{BROKEN}: the reason is that stderr line ({row.get('reason')})")
    check(not os.path.exists(os.path.join(d, "summary.json")), f"{BROKEN}: no summary.json")
    later = [n for n in os.listdir(os.path.join(d, "logs")) if n.endswith(".json") and not n.startswith("cleansing")]
    check(not later, f"{BROKEN}: no stage after cleansing recorded as done ({later})")


def check_summary(out, reason_expected=True):
    rows = {}
    with open(os.path.join(out, "cohort_summary.csv"), newline="") as f:
        for r in csv.DictReader(f):
            rows[r["case"]] = r
    check(sorted(rows) == sorted(GOOD + (BROKEN,)), f"cohort_summary.csv has one row per case ({sorted(rows)})")
    for c in GOOD:
        r = rows.get(c, {})
        check(r.get("status") == "done" and r.get("report") == f"{c}/report.html",
              f"{c}: done in cohort_summary.csv, with its report link")
        try:
            e = float(r.get("mean_error_mm", ""))
            check(0 < e < 10, f"{c}: mean registration error from the truth ({e} mm)")
        except ValueError:
            check(False, f"{c}: mean registration error in cohort_summary.csv ({r.get('mean_error_mm')})")
        check(all(r.get(f"seconds {s}") for s in STAGES), f"{c}: every stage's seconds in cohort_summary.csv")
    if BROKEN in rows:
        check_broken_case(out, rows[BROKEN])
    html = open(os.path.join(out, "cohort_summary.html")).read()
    import html as h
    check(h.escape(rows.get(BROKEN, {}).get("reason", "?")) in html, "cohort_summary.html shows the failed case's reason")
    check(all(f"href='{c}/report.html'" in html for c in GOOD), "cohort_summary.html links each case's report")
    return rows


def test_local(a):
    work = os.path.join(a.work, "local")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    findings = os.path.join(work, "phantom-s1_findings.mrk.json")
    shutil.copy(os.path.join(a.data, "phantom-s1", "supine_polyps.mrk.json"), findings)
    table, out = os.path.join(work, "cases.csv"), os.path.join(work, "out")
    write_table(table, GOOD + (BROKEN,), a.data, {"phantom-s1": findings})
    r, seconds = run_cohort(a, table, out)
    check(r.returncode == 1, f"run-cohort.sh exits 1 when a case failed ({r.returncode})")
    check(seconds <= 120, f"3-case cohort in <= 2 min ({seconds:.1f} s)")
    check(re.search(rf"^cohort: {BROKEN}: failed at 'segmentation supine': ColonSegmentation: error: ", r.stdout, re.M)
          is not None, "the failed case and its reason are printed")
    for c in GOOD:
        check_good_case(out, c)
    check_summary(out)
    first = journal(out)
    want = [(c, s) for c in GOOD for s in STAGES + ["report"]] + [(BROKEN, s) for s in STAGES[:2] + STAGES[3:5]]
    check(started(first) == sorted(want), "the first run ran every stage of the good cases, the broken one up to segmentation")

    # Nothing changed: only the failed stages run again (and fail again).
    r, _ = run_cohort(a, table, out)
    again = started(journal(out)[len(first):])
    check(again == sorted([(BROKEN, "segmentation prone"), (BROKEN, "segmentation supine")]),
          f"a rerun runs only the failed stages ({again})")
    # A changed input: the stages that read it, and what depends on them, in that case only.
    n = len(journal(out))
    with open(findings) as f:
        points = json.load(f)
    points["markups"][0]["controlPoints"] = points["markups"][0]["controlPoints"][:2]
    with open(findings, "w") as f:
        json.dump(points, f, indent=2)
    r, _ = run_cohort(a, table, out)
    changed = [x for x in started(journal(out)[n:]) if x[0] != BROKEN]
    check(changed == sorted([("phantom-s1", "transfer findings"), ("phantom-s1", "endoluminal views"),
                             ("phantom-s1", "report")]),
          f"a changed findings file reruns only transfer, views and report of that case ({changed})")
    s = json.load(open(os.path.join(out, "phantom-s1", "summary.json")))
    check(len(s["findings"]) == 2, f"the new report has the changed findings ({len(s['findings'])})")
    finish(work)


def group_members(pgid):
    """Live (not zombie) processes of a process group, from /proc."""
    members = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == pgid and fields[0] != "Z":
            members.append(int(pid))
    return members


def test_resume(a):
    work = os.path.join(a.work, "resume")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    table, out = os.path.join(work, "cases.csv"), os.path.join(work, "out")
    case = "phantom-s2"
    write_table(table, (case,), a.data)
    cmd = ["bash", os.path.join(a.repo, "scripts", "run-cohort.sh"), table, out, "--cli", a.cli]
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    deadline, killed_at = time.time() + 90, None
    while time.time() < deadline and p.poll() is None:
        if any(s == "landmarks" and e == "start" for _t, _c, s, e in journal(out)):
            os.killpg(p.pid, signal.SIGKILL)  # the whole run at once, as a power cut or `kill -9` would
            killed_at = time.time()
            break
        time.sleep(0.02)
    p.wait()
    check(killed_at is not None, "the run was killed while its landmarks stage ran")
    left = group_members(p.pid)
    for _ in range(100):  # SIGKILLed processes take a moment to go (zombies do not count)
        if not left:
            break
        time.sleep(0.1)
        left = group_members(p.pid)
    check(not left, f"nothing of the killed run is left running ({left})")
    logs = os.path.join(out, case, "logs")
    done = {s for s in STAGES + ["report"] if os.path.exists(os.path.join(logs, s.replace(" ", "_") + ".json"))}
    expect_done = set(STAGES[:6])
    check(done == expect_done, f"at the kill, exactly the six stages before landmarks were done ({sorted(done)})")
    before = {s: os.stat(os.path.join(logs, s.replace(" ", "_") + ".json")).st_mtime_ns for s in done}
    n = len(journal(out))

    r, seconds = run_cohort(a, table, out)
    check(r.returncode == 0, f"the resumed run completes ({r.returncode})")
    rerun = started(journal(out)[n:])
    expect = sorted((case, s) for s in STAGES[6:] + ["report"])
    check(rerun == expect, f"the resumed run ran only the unfinished stages ({[s for _c, s in rerun]})")
    after = {s: os.stat(os.path.join(logs, s.replace(" ", "_") + ".json")).st_mtime_ns for s in done}
    check(after == before, "the finished stages' records are untouched")
    check_good_case(out, case)
    finish(work)


def daemons_with(conf_dir):
    """Pids of processes whose command line names the cluster folder (munged, slurmctld, slurmd)."""
    pids = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                if conf_dir.encode() in f.read():
                    pids.append(int(pid))
        except OSError:
            pass
    return [p for p in pids if p != os.getpid()]


def test_slurm(a):
    work = os.path.join(a.work, "slurm")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    cluster = os.path.join(work, "cluster")
    missing = [t for t in ("munged", "slurmctld", "slurmd", "sbatch", "scontrol") if not shutil.which(t)]
    if not check(not missing, f"Slurm and munge installed (missing: {missing}; scripts/debian-packages.txt)"):
        finish()
    # slurm_local.py run: starts the cluster, runs the cohort on it, cancels what is left and stops
    # the daemons, also when this test dies (it gets SIGTERM then, see run_cohort).
    table, out = os.path.join(work, "cases.csv"), os.path.join(work, "out")
    write_table(table, GOOD + (BROKEN,), a.data)
    prefix = (sys.executable, os.path.join(a.repo, "scripts", "cohort", "slurm_local.py"), "run", cluster, "--")
    try:
        r, seconds = run_cohort(a, table, out, "--cluster", "slurm", "--jobs", "4", timeout=300, prefix=prefix)
        check(os.path.exists(os.path.join(cluster, "log", "slurmd.log")) and "cannot start" not in r.stderr,
              "a single-node cluster started (munged, slurmctld, slurmd)")
        check(r.returncode == 1, f"run-cohort.sh --cluster slurm exits 1 when a case failed ({r.returncode})")
        for c in GOOD:
            check_good_case(out, c)
        check_summary(out)
        # The stages ran as Slurm jobs: one per scan for cleansing..surface, one for the rest.
        logs = sorted(os.listdir(os.path.join(out, ".cohort", "slurm")))
        per_case = {c: sum(1 for l in logs if re.fullmatch(rf"\d+-{re.escape(c)}\.log", l)) for c in GOOD + (BROKEN,)}
        check(per_case == {"phantom-s1": 3, "phantom-s2": 3, BROKEN: 2}, f"Slurm jobs per case ({per_case})")
        check("jobs still queued" not in r.stderr, "no job left in the queue at the end")
        print(f"slurm cohort wall time {seconds:.1f} s (with starting and stopping the cluster)", flush=True)
    finally:
        left = daemons_with(cluster)
        for pid in left:  # belt and braces: nothing of ours may outlive the test
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass
        check(not left, f"the cluster is stopped, nothing left running ({left})")
    finish(work)


def test_report_only(a):
    work = os.path.join(a.work, "report-only")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    case = os.path.join(a.data, "phantom-s1")
    out, copy = os.path.join(work, "whole"), os.path.join(work, "again")
    exe = os.path.join(a.cli, "ColonSupineProne")
    inputs = ["--supine", f"{case}/supine.nrrd", "--prone", f"{case}/prone.nrrd",
              "--findings", f"{case}/supine_polyps.mrk.json", "--groundTruth", case]
    r = subprocess.run([exe, *inputs, "--outputDirectory", out, "--targetFaces", "40000"],
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if not check(r.returncode == 0, f"ColonSupineProne runs the whole pipeline ({r.stderr.strip()})"):
        finish()
    shutil.copytree(out, copy)
    os.remove(os.path.join(copy, "summary.json"))
    os.remove(os.path.join(copy, "report.html"))
    s = json.load(open(os.path.join(out, "summary.json")))
    records = os.path.join(work, "records.json")
    with open(records, "w") as f:
        json.dump({"stages": s["stages"], "stageBlocks": s.get("stageBlocks", []), "notes": s["notes"]}, f)
    ret = os.path.join(work, "returns.txt")
    r = subprocess.run([exe, "--reportOnly", *inputs, "--outputDirectory", copy, "--stageRecords", records,
                        "--returnparameterfile", ret], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    check(r.returncode == 0, f"--reportOnly succeeds ({r.stderr.strip()})")
    for name in ("summary.json", "report.html"):
        same = open(os.path.join(out, name), "rb").read() == open(os.path.join(copy, name), "rb").read()
        check(same, f"--reportOnly writes {name} byte for byte as the whole run did")
    rp = dict(l.rstrip("\n").split(" = ", 1) for l in open(ret) if " = " in l)
    check(rp.get("warnings") == str(s["warnings"]) and float(rp.get("meanError", "nan")) > 0,
          f"--reportOnly return parameters ({rp})")
    # A stage file with a field of another type than the report reads (edited by hand) is the
    # folder's problem: one line naming it, no "internal error", nothing written.
    spoilt = os.path.join(work, "spoilt")
    shutil.copytree(copy, spoilt)
    for name in ("summary.json", "report.html"):
        os.remove(os.path.join(spoilt, name))
    reg_json = os.path.join(spoilt, "registration", "registration.json")
    reg = json.load(open(reg_json))
    for seg in reg.get("segments", {}).values():
        if isinstance(seg, dict) and "trusted" in seg:
            seg["trusted"] = "yes"
    json.dump(reg, open(reg_json, "w"))
    r = subprocess.run([exe, "--reportOnly", *inputs, "--outputDirectory", spoilt, "--stageRecords", records],
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    lines = r.stderr.strip().splitlines()
    check(r.returncode != 0 and len(lines) == 1 and spoilt in lines[0] and "internal error" not in lines[0]
          and not os.path.exists(os.path.join(spoilt, "summary.json")),
          f"--reportOnly on a hand-spoilt registration.json fails with one line naming the folder ({r.stderr.strip()})")
    # Without the stage folders it refuses, naming what is missing, and writes nothing.
    empty = os.path.join(work, "empty")
    os.makedirs(empty)
    r = subprocess.run([exe, "--reportOnly", "--outputDirectory", empty], capture_output=True, text=True)
    check(r.returncode != 0 and "has no landmarks/supine/landmarks.json" in r.stderr and not os.listdir(empty),
          f"--reportOnly on a folder without stages fails with one line ({r.stderr.strip()})")
    finish(work)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("test", choices=["local", "resume", "slurm", "report-only"])
    ap.add_argument("--repo", required=True)
    ap.add_argument("--cli", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    {"local": test_local, "resume": test_resume, "slurm": test_slurm, "report-only": test_report_only}[a.test](a)


if __name__ == "__main__":
    main()
