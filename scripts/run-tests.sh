#!/usr/bin/env bash
# Sets everything up (scripts/setup.sh) and runs the whole test suite with ctest.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${COLONMAP_BUILD_DIR:-$repo/build}
bash "$repo/scripts/setup.sh"
cd "$build/ColonMap-build"
# One virtual display for all the tests that render (Testing/with-display.sh uses it).
display=()
if [ -z "${DISPLAY:-}" ]; then display=(xvfb-run -a -s "-screen 0 1280x1024x24"); fi
"${display[@]}" ctest --output-on-failure -j "${COLONMAP_JOBS:-$(nproc)}" "$@"
