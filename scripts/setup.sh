#!/usr/bin/env bash
# Sets ColonMap up on a Debian machine: installs missing packages, configures the SuperBuild
# and builds (and installs into build/install). Re-running it only rebuilds what changed.
# Environment: COLONMAP_BUILD_DIR (default <repo>/build), COLONMAP_JOBS (default: all cores).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${COLONMAP_BUILD_DIR:-$repo/build}
bash "$repo/scripts/install-dependencies.sh"
start=$(date +%s)
cmake -S "$repo/SuperBuild" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j "${COLONMAP_JOBS:-$(nproc)}"
echo "ColonMap: built in $(( $(date +%s) - start )) s; modules in $build/ColonMap-build/lib/ColonMap/cli-modules"
