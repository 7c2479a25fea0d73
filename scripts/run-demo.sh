#!/usr/bin/env bash
# Sets everything up (scripts/setup.sh) and runs the main job on the built-in default input: a
# phantom supine/prone pair (ColonPhantom) through the whole pipeline (ColonSupineProne), with the
# phantom's polyps as findings and its ground truth for the error. Prints where the report is.
# Extra arguments go to ColonPhantom (e.g. --seed 7 --spacing 1,1,1).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${COLONMAP_BUILD_DIR:-$repo/build}
out=${COLONMAP_DEMO_DIR:-$repo/colonmap-demo}
cli=$build/ColonMap-build/lib/ColonMap/cli-modules
bash "$repo/scripts/setup.sh"
"$cli/ColonPhantom" --outputDirectory "$out/phantom" "$@"
# The endoluminal views render with Mesa; without a display, under a virtual one.
display=()
if [ -z "${DISPLAY:-}" ] && command -v xvfb-run > /dev/null; then display=(xvfb-run -a); fi
"${display[@]}" "$cli/ColonSupineProne" --supine "$out/phantom/supine.nrrd" --prone "$out/phantom/prone.nrrd" \
  --outputDirectory "$out" --findings "$out/phantom/supine_polyps.mrk.json" --groundTruth "$out/phantom" \
  | grep -v '^<filter'
echo "ColonMap: report in $out/report.html; stage outputs in $out/<stage>/, times and flags in $out/summary.json"
