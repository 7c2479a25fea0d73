#!/usr/bin/env bash
# Runs the ColonMap pipeline over a cohort (issue 25): one Snakemake rule per stage, per case, over
# a case table; resumes where a previous run stopped; writes OUT/cohort_summary.{csv,html,json}.
#
#   scripts/run-cohort.sh CASES.csv OUT [--cluster slurm] [--jobs N] [--method M] [--target-faces N]
#                         [--skip-views] [--cli DIR] [-- SNAKEMAKE ARGS...]
#
# Local by default, on all cores of this machine (--jobs N: N cores). --cluster slurm submits each
# stage as a Slurm job with the profile scripts/cohort/profiles/slurm (--jobs N: at most N jobs
# queued at once, default 100). Exit status 0 when every case is done, 1 when a case failed or did
# not finish (listed on stdout, with its reason), 2 on a usage or case-table error.
# Guide: docs/cohorts.md.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(dirname "$here")"
usage() { sed -n '4,6p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2; exit 2; }

[ $# -ge 2 ] || usage
table="$1" out="$2"; shift 2
cluster="" jobs="" method="harmonic" faces="200000" skip_views="false"
cli="${COLONMAP_CLI_DIR:-$repo/build/ColonMap-build/lib/ColonMap/cli-modules}"
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --cluster) cluster="${2:-}"; shift 2 ;;
    --jobs) jobs="${2:-}"; shift 2 ;;
    --method) method="${2:-}"; shift 2 ;;
    --target-faces) faces="${2:-}"; shift 2 ;;
    --skip-views) skip_views="true"; shift ;;
    --cli) cli="${2:-}"; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    *) echo "run-cohort: unknown option '$1'" >&2; usage ;;
  esac
done
case "$cluster" in ""|local|slurm) ;; *) echo "run-cohort: --cluster: 'slurm' (or nothing: local)" >&2; exit 2 ;; esac
if [ -n "$jobs" ] && ! [[ "$jobs" =~ ^[1-9][0-9]*$ ]]; then echo "run-cohort: --jobs: a positive number" >&2; exit 2; fi
command -v snakemake >/dev/null || { echo "run-cohort: snakemake not found (apt-get install snakemake)" >&2; exit 2; }
[ -x "$cli/ColonSupineProne" ] || { echo "run-cohort: no ColonMap modules in '$cli' (build first: scripts/setup.sh, or --cli DIR)" >&2; exit 2; }
[ -f "$table" ] || { echo "run-cohort: case table '$table' does not exist" >&2; exit 2; }
table="$(cd "$(dirname "$table")" && pwd)/$(basename "$table")"
cli="$(cd "$cli" && pwd)"

# The table is checked whole before any work: every problem listed, nothing run.
python3 - "$here/cohort" "$table" <<'EOF' || exit 2
import sys
sys.path.insert(0, sys.argv[1])
import cohort
try:
    cases = cohort.read_cases(sys.argv[2])
except cohort.TableError as e:
    sys.exit(f"run-cohort: {e}")
print(f"run-cohort: {len(cases)} cases in {sys.argv[2]}")
EOF

mkdir -p "$out/.cohort/slurm"
out="$(cd "$out" && pwd)"
# One run per output folder at a time. The kernel drops this lock when the run dies in any way
# (even kill -9), so a killed run never leaves a stale lock (Snakemake's own lock is off: nolock).
exec 9>"$out/.cohort/run.lock"
flock -n 9 || { echo "run-cohort: another run is using '$out'" >&2; exit 2; }

args=(--snakefile "$here/cohort/Snakefile" --directory "$out"
      --config "cases=$table" "cli=$cli" "method=$method" "target_faces=$faces" "skip_views=$skip_views")
if [ "$cluster" = slurm ]; then
  command -v sbatch >/dev/null || { echo "run-cohort: --cluster slurm: sbatch not found" >&2; exit 2; }
  args+=(--profile "$here/cohort/profiles/slurm")
  [ -n "$jobs" ] && args+=(--jobs "$jobs")
else
  args+=(--profile "$here/cohort/profiles/local" --cores "${jobs:-$(nproc)}")
fi

log="$out/.cohort/run-$(date -u +%Y%m%dT%H%M%SZ)-$$.log"
echo "run-cohort: output in $out (Snakemake log: $log)"
set +e
# In the background so that a TERM/INT/HUP sent to this script reaches Snakemake at once (it then
# stops its jobs, on Slurm with scancel); wait again until it has finished doing so.
snakemake "${args[@]}" "${extra[@]}" >"$log" 2>&1 &
sm=$!
trap 'kill -TERM $sm 2>/dev/null' TERM INT HUP
wait $sm
rc=$?
while kill -0 $sm 2>/dev/null; do wait $sm; rc=$?; done
trap - TERM INT HUP
set -e
# The summary is also written by the workflow's onsuccess/onerror; this makes sure it is current
# even when Snakemake stopped before starting (and prints the cases that did not finish).
python3 "$here/cohort/cohort_summary.py" "$table" "$out" || true
if [ $rc -ne 0 ] && ! grep -q "^cohort: " "$log"; then
  tail -n 20 "$log" >&2
fi
[ $rc -eq 0 ] || exit 1
python3 - "$out/cohort_summary.json" <<'EOF'
import json, sys
rows = json.load(open(sys.argv[1]))["cases"]
sys.exit(0 if all(r["status"] == "done" for r in rows) else 1)
EOF
