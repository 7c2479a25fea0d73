#!/usr/bin/env bash
# Sets everything up (scripts/setup.sh) and runs the main job on the built-in default input, a
# phantom supine/prone pair, through the stages that exist (scripts/demo_pipeline.py).
# Extra arguments go to ColonPhantom (e.g. --seed 7 --spacing 1,1,1).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${COLONMAP_BUILD_DIR:-$repo/build}
out=${COLONMAP_DEMO_DIR:-$repo/colonmap-demo}
bash "$repo/scripts/setup.sh"
python3 "$repo/scripts/demo_pipeline.py" --cli-dir "$build/ColonMap-build/lib/ColonMap/cli-modules" \
  --output "$out" "$@"
