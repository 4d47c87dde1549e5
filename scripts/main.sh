#!/usr/bin/env bash
# The main job on a fresh Debian machine: install what is missing, build, and run the pipeline on the
# shipped data. Outputs go to out/ (override with OUT=...).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-out}
scripts/install-deps.sh
scripts/build.sh
start=$(date +%s%N)
build/pastemix lab reduce datasets/thesis --out "$out/lab"
build/pastemix lab drag-fit datasets/thesis --out "$out/drag"
end=$(date +%s%N)
awk -v ns="$((end - start))" -v out="$out" 'BEGIN { printf "main job: done in %.1f s; outputs in %s/\n", ns / 1e9, out }'
