#!/usr/bin/env python3
"""Snakemake --cluster-status for Slurm (issue 25): prints running, success or failed for a job id.

Asks scontrol first (works on clusters without accounting, as long as the job is younger than
MinJobAge), then sacct. A job Slurm no longer knows of is taken as failed only after sacct also
has nothing; a transient error of the Slurm commands counts as still running.
"""
import subprocess
import sys

RUNNING = {"PENDING", "CONFIGURING", "RUNNING", "COMPLETING", "SUSPENDED", "REQUEUED", "RESIZING", "SIGNALING",
           "STAGE_OUT", "REQUEUE_HOLD", "REQUEUE_FED", "RESV_DEL_HOLD", "STOPPED"}


def state_scontrol(job):
    r = subprocess.run(["scontrol", "-o", "show", "job", job], capture_output=True, text=True, timeout=30)
    if r.returncode != 0:
        return None
    for field in r.stdout.split():
        if field.startswith("JobState="):
            return field.split("=", 1)[1]
    return None


def state_sacct(job):
    try:
        r = subprocess.run(["sacct", "-n", "-X", "-P", "-j", job, "-o", "State"], capture_output=True, text=True,
                           timeout=30)
    except (OSError, subprocess.TimeoutExpired):
        return None
    lines = [l.strip() for l in r.stdout.splitlines() if l.strip()]
    return lines[0].split()[0] if r.returncode == 0 and lines else None


def main():
    job = sys.argv[1].split(";")[0].strip()
    try:
        state = state_scontrol(job) or state_sacct(job)
    except (OSError, subprocess.TimeoutExpired):
        print("running")
        return
    if state is None:
        print("failed")
    elif state in RUNNING:
        print("running")
    elif state == "COMPLETED":
        print("success")
    else:  # FAILED, CANCELLED, TIMEOUT, OUT_OF_MEMORY, NODE_FAIL, PREEMPTED, BOOT_FAIL, DEADLINE
        print("failed")


if __name__ == "__main__":
    main()
