#!/usr/bin/env python3
"""Runs one stage module for one case of a cohort and records it (issue 25).

    run_stage.py --case-dir DIR --stage "surface supine" --module ColonSurface [--threads N]
                 [--display] [--optional] [--copy SRC=DST ...] -- EXECUTABLE ARGS...

The record DIR/logs/<stage>.json (name, module, seconds, results = the module's return
parameters, as ColonSupineProne lists its stages) is written last, only when the module succeeded:
it is what the workflow (scripts/cohort/Snakefile) treats as "this stage is done". The module's
stdout (progress) and stderr go to DIR/logs/<stage>.stdout and .stderr. When the module fails,
DIR/logs/<stage>.failed says why (the module's one-line error from stderr) and the exit status is
the module's; a later success removes it. With --optional (the endoluminal views, which need a
display) a failure is recorded as a note instead and the stage counts as done, as in
ColonSupineProne. Every start and end is appended to the cohort journal (<out>/.cohort/journal.tsv,
out = the parent of DIR), which the tests read to see which stages ran.
"""
import argparse
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time


def slug(stage):
    return stage.replace(" ", "_")


def write_json(path, data):
    """Writes JSON atomically (temporary file in the same folder, then rename)."""
    folder = os.path.dirname(path)
    os.makedirs(folder, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=folder, prefix="." + os.path.basename(path) + ".")
    with os.fdopen(fd, "w") as f:
        json.dump(data, f, indent=2)
        f.write("\n")
    os.replace(tmp, path)


def journal(case_dir, case, stage, event, detail=""):
    out = os.path.dirname(os.path.abspath(case_dir))
    os.makedirs(os.path.join(out, ".cohort"), exist_ok=True)
    line = f"{time.time():.3f}\t{case}\t{stage}\t{event}\t{os.getpid()}\t{detail}\n"
    # One write() on an O_APPEND file: lines of concurrent stages do not interleave.
    fd = os.open(os.path.join(out, ".cohort", "journal.tsv"), os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
    try:
        os.write(fd, line.encode())
    finally:
        os.close(fd)


def read_returns(path):
    """A --returnparameterfile ("name = value" lines) as a dict."""
    results = {}
    try:
        with open(path) as f:
            for line in f:
                if " = " in line:
                    k, v = line.rstrip("\n").split(" = ", 1)
                    results[k.strip()] = v
    except OSError:
        pass
    return results


def error_line(stderr_path, module):
    """The module's one-line error ("<Module>: error: ...") from its stderr, else the last line."""
    try:
        with open(stderr_path, errors="replace") as f:
            lines = [l.strip() for l in f if l.strip()]
    except OSError:
        lines = []
    for line in reversed(lines):
        if re.match(rf"^{re.escape(module)}: error: ", line):
            return line
    for line in reversed(lines):
        if ": error: " in line:
            return line
    return lines[-1] if lines else ""


class VirtualDisplay:
    """An Xvfb of our own (-displayfd picks a free display without races) when there is no DISPLAY."""

    def __init__(self, wanted):
        self.proc = None
        self.display = os.environ.get("DISPLAY", "")
        if not wanted or self.display:
            return
        try:
            r, w = os.pipe()
            self.proc = subprocess.Popen(["Xvfb", "-displayfd", str(w), "-screen", "0", "1280x1024x24", "-nolisten", "tcp"],
                                         pass_fds=(w,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            os.close(w)
            with os.fdopen(r) as f:
                number = f.readline().strip()
            if number:
                self.display = ":" + number
            else:
                self.close()
        except OSError:
            self.proc = None  # no Xvfb: the module says what it cannot do without a display

    def close(self):
        if self.proc and self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
        self.proc = None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case-dir", required=True)
    ap.add_argument("--stage", required=True, help="stage name as in summary.json, e.g. 'surface supine'")
    ap.add_argument("--module", required=True)
    ap.add_argument("--threads", type=int, default=0, help="cores the module may use (0: all)")
    ap.add_argument("--display", action="store_true", help="the module renders: give it a virtual display if none")
    ap.add_argument("--optional", action="store_true", help="a failure is a note, not a failed stage")
    ap.add_argument("--copy", action="append", default=[], metavar="SRC=DST", help="copy a file after success")
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    cmd = a.command[1:] if a.command[:1] == ["--"] else a.command
    if not cmd:
        ap.error("no module command after --")

    case_dir = a.case_dir
    case = os.path.basename(os.path.abspath(case_dir))
    logs = os.path.join(case_dir, "logs")
    os.makedirs(logs, exist_ok=True)
    base = os.path.join(logs, slug(a.stage))
    record_path, failed_path = base + ".json", base + ".failed"
    returns = base + ".returns.txt"
    for stale in (record_path, returns):
        if os.path.exists(stale):
            os.remove(stale)

    env = dict(os.environ)
    if a.threads > 0:
        for var in ("ITK_GLOBAL_DEFAULT_NUMBER_OF_THREADS", "OMP_NUM_THREADS", "VTK_SMP_MAX_THREADS"):
            env[var] = str(a.threads)
    display = VirtualDisplay(a.display)
    if display.display:
        env["DISPLAY"] = display.display

    journal(case_dir, case, a.stage, "start")
    child = None

    def stop(signum, _frame):
        # Killed by Snakemake, Slurm (scancel, time limit) or the user: stop the module, say so.
        if child and child.poll() is None:
            child.terminate()
        display.close()
        write_json(failed_path, {"stage": a.stage, "module": a.module, "returncode": -signum,
                                 "reason": f"{a.module}: stopped by signal {signum} (killed or cancelled)"})
        journal(case_dir, case, a.stage, "killed", str(signum))
        sys.exit(128 + signum)

    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)
    start = time.time()
    with open(base + ".stdout", "w") as out, open(base + ".stderr", "w") as err:
        try:
            child = subprocess.Popen(cmd + ["--returnparameterfile", returns], stdout=out, stderr=err, env=env)
            rc = child.wait()
        except OSError as e:  # missing or unreadable executable (e.g. being rebuilt right now)
            err.write(f"{a.module}: error: cannot run '{cmd[0]}': {e.strerror}\n")
            rc = 127
    seconds = time.time() - start
    display.close()
    with open(base + ".stderr", errors="replace") as f:
        sys.stderr.write(f.read())  # into the Snakemake / Slurm log as well

    record = {"name": a.stage, "module": a.module, "seconds": seconds, "results": read_returns(returns)}
    if rc != 0:
        reason = error_line(base + ".stderr", a.module) or f"{a.module}: exit status {rc}, no message"
        if not a.optional:
            write_json(failed_path, {"stage": a.stage, "module": a.module, "returncode": rc, "reason": reason,
                                     "stderr": os.path.abspath(base + ".stderr")})
            journal(case_dir, case, a.stage, "failed", reason)
            return rc if rc > 0 else 1
        # As ColonSupineProne: the run stands without the endoluminal views, the report says why.
        reason = re.sub(rf"^{re.escape(a.module)}: error: ", "", reason)
        record = {"name": a.stage, "module": a.module, "skipped": True,
                  "note": f"No endoluminal views: {reason}"}
    for pair in a.copy:
        src, dst = pair.split("=", 1)
        tmp = dst + ".part"
        with open(src, "rb") as fi, open(tmp, "wb") as fo:
            fo.write(fi.read())
        os.replace(tmp, dst)
    if os.path.exists(failed_path):
        os.remove(failed_path)
    write_json(record_path, record)
    journal(case_dir, case, a.stage, "done", f"{seconds:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
