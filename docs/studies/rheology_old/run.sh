#!/usr/bin/env bash
# Runs the old assumed rheology (make_scenes.sh) for the mixing cases given, 3 seeds each (the scene's own seed
# and the next two: the same seeds as `pastemix predict rheology`), with the band's overrides, J runs at once,
# one thread each. A run whose result exists is not redone. Then scores each case against the lab
# (`pastemix score`, the 3 seeds as an ensemble), into OUT/case<N>/. Cases 1-5 (the issue compares 1, 4, 5).
# Usage: run.sh PASTEMIX SRC_TREE LAB_DIR OUT J CASE...
set -euo pipefail
px=$1 src=$2 lab=$3 out=$4 jobs=$5; shift 5
here=$(cd "$(dirname "$0")" && pwd)
"$here/make_scenes.sh" "$src" "$out/scenes"
one() {  # case seed
  local c=$1 s=$2 d="$out/case$1/seed$2"
  [[ -f "$d/mixing_case$1.h5" && -f "$d/done" ]] && return 0
  mkdir -p "$d"
  "$px" run "$out/scenes/mixing_case$c.toml" --overrides "$here/../rheology_band.overrides.toml" \
    --set "seed=$s" --threads 1 --quiet --out "$d" > "$d/run.log" 2>&1 && touch "$d/done"
}
export -f one; export px out here
for c in "$@"; do
  [[ $c -ge 1 && $c -le 5 ]] || { echo "run.sh: case $c: only cases 1-5 (those with a lab grid) are run" >&2; exit 2; }
done
for c in "$@"; do
  s0=$(grep -m1 '^seed *=' "$out/scenes/mixing_case$c.toml" | sed 's/[^0-9]//g')
  for k in 0 1 2; do echo "$c $((s0 + k))"; done
done | xargs -P "$jobs" -n 2 bash -c 'one "$0" "$1"'
for c in "$@"; do
  files=$(ls "$out"/case$c/seed*/mixing_case$c.h5)
  "$px" score $files --lab "$c" --lab-h5 "$lab/lab.h5" --out "$out/case$c/score" > "$out/case$c/score.txt"
done
