#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A real run killed with SIGKILL at a seeded random moment, at 1 and 2 threads, resumed with --resume, and
# compared bit for bit (scripts/h5compare.py) with an uninterrupted run that wrote no checkpoint (issue 20).
#   scripts/kill_resume_check.sh [SCENE] [END_TIME_S] [OUT]   # default: case 3, its first 0.15 s, /tmp/kill_resume
# PASTEMIX=path to another build (default build/pastemix). Exit 0 if both resumed results are identical.
set -u
cd "$(dirname "$0")/.."
B=${PASTEMIX:-$PWD/build/pastemix}
S=${1:-datasets/scenes/mixing_case3.toml}
END=${2:-0.15}
R=${3:-/tmp/kill_resume}
stem=$(basename "$S" .toml)
rm -rf "$R" && mkdir -p "$R"
"$B" run "$S" --set end_time="$END" --out "$R/ref" --threads 1 > "$R/ref.log" 2>&1 &
for th in 1 2; do
  (
    RANDOM=$((20261202 + th)); delay=$((40 + RANDOM % 50))   # s of wall clock before the kill
    "$B" run "$S" --set end_time="$END" --out "$R/k$th" --threads $th --checkpoint-every 10 > "$R/k$th.killed.log" 2>&1 &
    pid=$!
    sleep $delay
    if kill -0 $pid 2>/dev/null; then kill -9 $pid; echo "t$th: SIGKILL after $delay s"; else echo "t$th: ended before the kill"; fi
    wait $pid 2>/dev/null
    "$B" run "$S" --set end_time="$END" --out "$R/k$th" --threads $th --resume "$R/k$th" > "$R/k$th.resumed.log" 2>&1
    echo "t$th: resume exit $?, $(grep -o 'resumed at step [0-9]*' "$R/k$th.resumed.log")"
  ) &
done
wait
status=0
for th in 1 2; do
  echo "t$th against the uninterrupted run:"
  /usr/bin/python3 scripts/h5compare.py "$R/ref/$stem.h5" "$R/k$th/$stem.h5" || status=1
done
exit $status
