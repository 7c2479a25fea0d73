#!/usr/bin/env python3
"""A throw-away single-node Slurm cluster on this machine, for tests and demos (issue 25).

    slurm_local.py start DIR          # munged, slurmctld and slurmd, all files under DIR; prints the
                                      # line to export: SLURM_CONF=DIR/slurm.conf
    slurm_local.py stop DIR           # cancels its jobs, stops the daemons started with DIR
    slurm_local.py run DIR -- CMD...  # start, run CMD with SLURM_CONF set, stop; exit status CMD's

Everything (munge key and socket, slurm.conf, state, spool, logs, pid files) lives in DIR; the
daemons run as the calling user (root in CI) on free localhost ports. `start` waits until the node
is idle and stops what it started if it does not get there. With `run` nothing outlives it: on
SIGTERM, SIGINT or SIGHUP (e.g. its parent test died) it stops CMD's process group first (CMD
cancels its jobs while the cluster is still up), then cancels what is left in the queue, then
stops the daemons, which are its children and are killed by the kernel should it die itself.
Needs Debian's slurm-wlm and munge.
"""
import os
import shutil
import signal
import socket
import subprocess
import sys
import time


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def node_resources():
    """CPUs and RealMemory (MB) as slurmd sees this machine."""
    out = subprocess.run(["slurmd", "-C"], capture_output=True, text=True, check=True).stdout
    fields = dict(f.split("=", 1) for f in out.split() if "=" in f)
    return int(fields["CPUs"]), int(fields["RealMemory"])


def write_config(d):
    host = socket.gethostname().split(".")[0]
    cpus, memory = node_resources()
    user = os.environ.get("USER") or subprocess.run(["id", "-un"], capture_output=True, text=True).stdout.strip()
    for sub in ("state", "spool", "log", "munge"):
        os.makedirs(os.path.join(d, sub), exist_ok=True)
    os.chmod(os.path.join(d, "munge"), 0o700)
    key = os.path.join(d, "munge", "munge.key")
    if not os.path.exists(key):
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o600)
    conf = f"""# single-node test cluster written by scripts/cohort/slurm_local.py
ClusterName=colonmap-local
SlurmctldHost={host}(127.0.0.1)
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
SlurmUser={user}
SlurmdUser={user}
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={d}/munge/munge.socket
StateSaveLocation={d}/state
SlurmdSpoolDir={d}/spool
SlurmctldPidFile={d}/slurmctld.pid
SlurmdPidFile={d}/slurmd.pid
SlurmctldLogFile={d}/log/slurmctld.log
SlurmdLogFile={d}/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
MpiDefault=none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
MinJobAge=300
KillWait=5
NodeName={host} NodeAddr=127.0.0.1 CPUs={cpus} RealMemory={memory} State=UNKNOWN
PartitionName=local Nodes={host} Default=YES MaxTime=INFINITE State=UP
"""
    with open(os.path.join(d, "slurm.conf"), "w") as f:
        f.write(conf)
    return host


def pid_of(path):
    try:
        with open(path) as f:
            return int(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        return None


def alive(pid):
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except OSError:
        return False
    try:  # a zombie is not running
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return True


def cancel_jobs(d):
    """Cancels every job of the cluster of DIR and waits (at most 15 s) for the queue to empty."""
    conf = os.path.join(d, "slurm.conf")
    if not os.path.exists(conf) or not alive(pid_of(os.path.join(d, "slurmctld.pid")) or -1):
        return
    env = dict(os.environ, SLURM_CONF=conf)
    subprocess.run(["scancel", "--quiet", "--user", str(os.getuid())], env=env, capture_output=True, timeout=30)
    deadline = time.time() + 15
    while time.time() < deadline:
        r = subprocess.run(["squeue", "-h", "-o", "%i"], env=env, capture_output=True, text=True, timeout=30)
        if r.returncode != 0 or not r.stdout.strip():
            return
        time.sleep(0.5)


def stop(d):
    """Cancels the cluster's jobs, then stops slurmd, slurmctld and munged of DIR: SIGTERM, then
    SIGKILL after 10 s. Returns the pids still running afterwards (none, normally)."""
    d = os.path.abspath(d)
    try:
        cancel_jobs(d)
    except (OSError, subprocess.TimeoutExpired):
        pass
    pids = [p for p in (pid_of(os.path.join(d, n)) for n in ("slurmd.pid", "slurmctld.pid", "munged.pid")) if p]
    for p in pids:
        if alive(p):
            os.kill(p, signal.SIGTERM)
    deadline = time.time() + 10
    while time.time() < deadline and any(alive(p) for p in pids):
        time.sleep(0.2)
    for p in pids:
        if alive(p):
            os.kill(p, signal.SIGKILL)
    return [p for p in pids if alive(p)]


def run(cmd, env):
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {r.returncode}: {(r.stderr or r.stdout).strip()}")
    return r.stdout


def tail(path, n=15):
    try:
        with open(path, errors="replace") as f:
            return "".join(f.readlines()[-n:])
    except OSError:
        return "(no log)\n"


def _die_with_parent():
    """In the child before exec: the kernel sends SIGKILL when the parent dies (PR_SET_PDEATHSIG)."""
    import ctypes
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)


def start(d, tied=False):
    """Starts the cluster of DIR. tied: the daemons run in the foreground as children of this
    process and die with it, however it ends (a test killed by its time limit leaves nothing);
    returns their Popen objects. Otherwise they run as daemons until `stop`."""
    d = os.path.abspath(d)
    for tool in ("munged", "slurmctld", "slurmd", "sinfo"):
        if not shutil.which(tool):
            sys.exit(f"slurm_local: {tool} not found (apt-get install slurm-wlm munge)")
    host = write_config(d)
    env = dict(os.environ, SLURM_CONF=os.path.join(d, "slurm.conf"))
    m = os.path.join(d, "munge")
    children = []

    def launch(cmd, foreground_flag):
        if not tied:
            run(cmd, env)
            return
        log = open(os.path.join(d, "log", os.path.basename(cmd[0]) + ".out"), "w")
        children.append(subprocess.Popen(cmd + [foreground_flag], env=env, stdout=log, stderr=subprocess.STDOUT,
                                         stdin=subprocess.DEVNULL, preexec_fn=_die_with_parent))

    try:
        launch(["munged", "--force", f"--socket={m}/munge.socket", f"--key-file={m}/munge.key",
                f"--pid-file={d}/munged.pid", f"--log-file={d}/log/munged.log", f"--seed-file={m}/munged.seed"], "-F")
        for _ in range(50):  # the daemons need munge's socket
            if os.path.exists(f"{m}/munge.socket"):
                break
            time.sleep(0.1)
        launch(["slurmctld", "-f", env["SLURM_CONF"]], "-D")
        launch(["slurmd", "-f", env["SLURM_CONF"], "-N", host], "-D")
        deadline = time.time() + 60
        state = ""
        while time.time() < deadline:
            r = subprocess.run(["sinfo", "-h", "-N", "-o", "%T"], env=env, capture_output=True, text=True)
            state = r.stdout.strip()
            if state in ("idle", "mixed", "allocated"):
                break
            time.sleep(0.5)
        else:
            raise RuntimeError(f"node not idle after 60 s (state '{state}')\nslurmctld.log:\n"
                               + tail(f"{d}/log/slurmctld.log") + "slurmd.log:\n" + tail(f"{d}/log/slurmd.log"))
    except Exception as e:  # noqa: BLE001 - report, clean up, fail
        stop(d)
        for c in children:
            if c.poll() is None:
                c.kill()
        if tied:
            raise RuntimeError(f"slurm_local: cannot start the cluster: {e}") from e
        sys.exit(f"slurm_local: cannot start the cluster: {e}")
    if tied:
        return children
    print(f"SLURM_CONF={env['SLURM_CONF']}")


class Stopped(Exception):
    pass


def say(text):
    """A line on stderr; never fails (the reader may be gone: a killed parent's pipe)."""
    try:
        print(text, file=sys.stderr, flush=True)
    except OSError:
        pass


def run_with_cluster(d, cmd):
    """Starts the cluster of DIR, runs CMD (its own process group) with SLURM_CONF, stops the
    cluster; returns CMD's exit status (2 when the cluster does not start, 3 when a daemon would
    not stop)."""
    d = os.path.abspath(d)

    def on_signal(signum, _frame):
        raise Stopped(signum)

    for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(s, on_signal)
    daemons, child, rc = [], None, 1
    try:
        try:
            daemons = start(d, tied=True)
        except RuntimeError as e:
            say(str(e))
            return 2
        env = dict(os.environ, SLURM_CONF=os.path.join(d, "slurm.conf"))
        child = subprocess.Popen(cmd, env=env, start_new_session=True)
        rc = child.wait()
    except Stopped as e:
        rc = 128 + e.args[0]
        if child and child.poll() is None:
            os.killpg(child.pid, signal.SIGTERM)
            say(f"slurm_local: stopped by signal {e.args[0]}: stopping {cmd[0]}")
            try:
                child.wait(30)
            except subprocess.TimeoutExpired:
                os.killpg(child.pid, signal.SIGKILL)
                child.wait()
    finally:
        for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
            signal.signal(s, signal.SIG_IGN)  # the clean-up below is not interrupted
        env = dict(os.environ, SLURM_CONF=os.path.join(d, "slurm.conf"))
        try:
            q = subprocess.run(["squeue", "-h", "-o", "%i %j %T"], env=env, capture_output=True, text=True,
                               timeout=30) if daemons else None
            if q and q.returncode == 0 and q.stdout.strip():
                say("slurm_local: jobs still queued at the end, cancelled: " + " | ".join(q.stdout.split("\n")))
        except (OSError, subprocess.TimeoutExpired):
            pass
        left = stop(d) if daemons else []
        for p in daemons:
            try:
                p.wait(10)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        if left:
            say(f"slurm_local: still running: {left}")
            rc = 3
    return rc


def main():
    if len(sys.argv) >= 4 and sys.argv[1] == "run" and sys.argv[3] == "--" and len(sys.argv) > 4:
        sys.exit(run_with_cluster(sys.argv[2], sys.argv[4:]))
    if len(sys.argv) != 3 or sys.argv[1] not in ("start", "stop"):
        sys.exit(__doc__)
    if sys.argv[1] == "start":
        start(sys.argv[2])
    else:
        left = stop(sys.argv[2])
        if left:
            sys.exit(f"slurm_local: still running: {left}")


if __name__ == "__main__":
    main()
