#!/usr/bin/env bash
# Issue 18's cost table: every coupling acceptance case once, one thread, in one go, each with its result line
# and its wall time (s). Not a speed claim (bench/ is); the time each case costs on the machine it runs on.
# Usage: scripts/coupling_costs.sh [PASTEMIX] > costs.txt   (needs out/lab/parameters.toml for steel-balls)
set -uo pipefail
px=${1:-build/pastemix}
export OMP_NUM_THREADS=1
one() {  # label, then the command's arguments
  local label=$1; shift
  local t0 t1 out rc
  t0=$(date +%s.%N)
  out=$("$px" "$@" 2>&1); rc=$?
  t1=$(date +%s.%N)
  printf '%-34s | %7.1f s | rc %d | pastemix %s\n' "$label" "$(echo "$t1 - $t0" | bc)" "$rc" "$*"
  printf '%s\n' "$out" | grep -vE '^\s*$' | tail -${TAIL:-2} | sed 's/^/    /'
}
echo "# coupling costs, $(date -u +%FT%TZ), $px at git $(git rev-parse --short HEAD 2>/dev/null), load $(cut -d' ' -f1-3 /proc/loadavg)"
one "sphere Newtonian h/d 1" validate coupling sphere --cell-over-d 1 --box-over-d 8
one "sphere Newtonian h/d 0.5" validate coupling sphere --cell-over-d 0.5 --box-over-d 8
one "sphere Newtonian h/d 0.25" validate coupling sphere --cell-over-d 0.25 --box-over-d 8
one "sphere Newtonian h/d 2 (L/d 24)" validate coupling sphere --cell-over-d 2 --box-over-d 24
one "sphere h/d 2 (L/d 16) cell centre" validate coupling sphere --cell-over-d 2 --box-over-d 16 --start 3.5 3.5
one "sphere h/d 2 (L/d 16) on faces" validate coupling sphere --cell-over-d 2 --box-over-d 16 --start 4 4
one "sphere Newtonian h/d 4 (L/d 32)" validate coupling sphere --cell-over-d 4 --box-over-d 32
one "sphere Bingham Y 0.08 (stops)" validate coupling sphere --yield-number 0.08
one "sphere Bingham Y 0.03 (moves)" validate coupling sphere --yield-number 0.03
one "piston (no DEM)" validate coupling piston
one "piston-dem 5 mm cells" validate coupling piston-dem --eta 0.5 --settle 3
one "hindered phi 0.1" validate coupling hindered --phi 0.1
for k in 1 10 100; do
  one "bed interval $k" validate coupling bed --intervals $k
  one "stream interval $k" validate coupling stream --intervals $k
done
one "dense stream scene (interval 50)" run datasets/scenes/flow_stream_small.toml --threads 1 --quiet --out /tmp/coupling_costs_fss
TAIL=6 one "steel balls flow 13.3 mm cells" validate steel-balls --curve published_4_19 --flow 0.0133
if "$px" validate coupling --help 2>&1 | grep -qE '^ +raft '; then
  one "raft q = 3 (holds)" validate coupling raft --load 3
  one "raft q = 12 (punches in)" validate coupling raft --load 12
  for k in 10 25; do  # the coupling interval near the capacity (Skempton's 5-9): below holds, above goes
    one "raft q = 5, interval $k" validate coupling raft --load 5 --interval $k
    one "raft q = 9, interval $k" validate coupling raft --load 9 --interval $k
  done
fi
