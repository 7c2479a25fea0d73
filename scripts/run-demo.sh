#!/usr/bin/env bash
# Sets everything up (scripts/setup.sh) and runs the main job on the built-in default input: a
# phantom supine/prone pair. Extra arguments go to ColonPhantom (e.g. --seed 7 --spacing 1,1,1).
# Today the pipeline stops after the phantom: the later stages are open issues (see README).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${COLONMAP_BUILD_DIR:-$repo/build}
out=${COLONMAP_DEMO_DIR:-$repo/colonmap-demo}
bash "$repo/scripts/setup.sh"
cli="$build/ColonMap-build/lib/ColonMap/cli-modules"
mkdir -p "$out"
start=$(date +%s.%N)
"$cli/ColonPhantom" --outputDirectory "$out/phantom" "$@"
end=$(date +%s.%N)
python3 - "$out" "$start" "$end" <<'PY'
import json, os, sys
out, start, end = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
truth = json.load(open(os.path.join(out, "phantom", "truth.json")))
summary = {"stages": {"phantom": round(end - start, 2)},
           "stagesNotYetAvailable": ["cleansing", "segmentation", "surface", "landmarks",
                                     "flattening", "registration", "views", "report"],
           "phantom": {k: truth[k] for k in ("colonLengthMm", "polyps") if k in truth}}
json.dump(summary, open(os.path.join(out, "summary.json"), "w"), indent=2)
PY
echo "ColonMap demo: phantom pair and ground truth in $out/phantom, summary in $out/summary.json"
echo "ColonMap demo: the registration stages and report are not built yet (README, Status)"
