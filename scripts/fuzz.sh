#!/usr/bin/env bash
# Builds the fuzz targets of Testing/Fuzz with clang (libFuzzer + ASan + UBSan) into build/fuzz and
# runs each for the given number of seconds (default 10) over a copy of its seed corpus, one
# process on one core. Prints per target: executions, coverage (cov/ft), duration; writes
# build/fuzz/fuzz-summary.json. Exits non-zero on any finding (crash, sanitizer report, timeout,
# out of memory, contract violation); the input is kept in build/fuzz/artifacts/.
# Usage: bash scripts/fuzz.sh [seconds, 0 = build only] [target ...]   (targets: markups imageheaders cameras commandline mesh reports)
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-10}
shift || true
build=${COLONMAP_FUZZ_BUILD_DIR:-$repo/build/fuzz}
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(markups imageheaders cameras commandline mesh reports)
declare -A exe=([markups]=FuzzMarkups [imageheaders]=FuzzImageHeaders [cameras]=FuzzCameras [commandline]=FuzzCommandLine [mesh]=FuzzMesh [reports]=FuzzReports)

lock=()
if command -v flock >/dev/null; then lock=(flock /tmp/colonmap-build.lock); fi
if [ ! -f "$build/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S "$repo/Testing/Fuzz" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=None >/dev/null
fi
# Only the chosen targets are built: a 10-minute run of one target waits for no other's build.
build_targets=()
for t in "${targets[@]}"; do
  [ -n "${exe[$t]:-}" ] || { echo "fuzz.sh: unknown target '$t'" >&2; exit 2; }
  build_targets+=("${exe[$t]}")
done
"${lock[@]}" ninja -C "$build" "${build_targets[@]}" >/dev/null
[ "$seconds" = 0 ] && exit 0  # 0 seconds: build only (libFuzzer would take 0 as no limit)

mkdir -p "$build/artifacts" "$build/logs"
summary="$build/fuzz-summary.json"
failed=0
entries=()
for t in "${targets[@]}"; do
  [ -n "${exe[$t]:-}" ] || { echo "fuzz.sh: unknown target '$t'" >&2; exit 2; }
  work="$build/corpus-$t"
  rm -rf "$work"
  mkdir -p "$work"
  cp "$repo/Testing/Fuzz/corpus/$t/"* "$work/"
  log="$build/logs/$t.log"
  dict=()
  [ -f "$repo/Testing/Fuzz/dict/$t.dict" ] && dict=(-dict="$repo/Testing/Fuzz/dict/$t.dict")
  start=$(date +%s)
  rc=0
  (cd "$build" && "./${exe[$t]}" -max_total_time="$seconds" -timeout=5 -rss_limit_mb=2048 -max_len=4096 \
      -print_final_stats=1 -artifact_prefix="$build/artifacts/$t-" "${dict[@]}" "$work") >"$log" 2>&1 || rc=$?
  duration=$(( $(date +%s) - start ))
  # libFuzzer's last status line: "#N  DONE cov: C ft: F corp: ..." and "stat::number_of_executed_units: N"
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")
  corp=$(ls "$work" | wc -l)
  status=ok
  if [ "$rc" -ne 0 ]; then status=finding; failed=1; fi
  printf '%-13s %-8s executions %-10s cov %-6s ft %-6s corpus %-5s %4ss\n' "$t" "$status" "${runs:-?}" "${cov:-?}" "${ft:-?}" "$corp" "$duration"
  if [ "$status" != ok ]; then
    grep -E 'ERROR|runtime error|CONTRACT|Test unit written|SUMMARY' "$log" | head -5 | sed 's/^/    /'
  fi
  entries+=("{\"target\": \"$t\", \"status\": \"$status\", \"seconds\": $seconds, \"duration\": $duration, \"executions\": ${runs:-null}, \"cov\": ${cov:-null}, \"ft\": ${ft:-null}, \"corpus\": $corp, \"log\": \"$log\"}")
done
{
  echo "["
  for i in "${!entries[@]}"; do
    sep=","; [ "$i" -eq $(( ${#entries[@]} - 1 )) ] && sep=""
    echo "  ${entries[$i]}$sep"
  done
  echo "]"
} >"$summary"
echo "summary: $summary"
exit $failed
