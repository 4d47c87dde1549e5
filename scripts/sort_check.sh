#!/usr/bin/env bash
# Tolerance check of the spatial sort of the particle store ([neighbor] sort_every, model/world.cpp): the
# same scenes with the default sort and with `--sort-every 0`, compared by scripts/compare_settled.py (settled
# statistics; the sort changes the order of force sums, so the chaotic flows diverge from round-off on).
# With --ref OLD, the same check of any engine change that moves the rounding (issue 19: the rebuild test of
# model/motion.h rebuilds at other steps): --bin's default run against OLD's default run, OLD sorted every
# 16th rebuild as case 3's round-off floor.
# Exit 0 when every case is within its tolerances, 1 otherwise.
#
#   scripts/sort_check.sh [--bin build/pastemix] [--ref OLD] [--work DIR] [--cases "pour bed case3"]
#                         [--case3-mass 0.2] [--lab-h5 out/lab/lab.h5]
#
# Cases:
#   pour, bed   the bench scenes, 2000 steps, constant-torque rolling, 1 thread (compare_settled.py state)
#   case3       mixing_case3 + the mixing_fast overrides, rock mass --case3-mass kg, to rest (its [stop]
#               rule), 1 thread; `pastemix maps --lab 3` of both and of a third run sorted every 16th
#               rebuild (the round-off floor); C per block within max(0.1 pp, 1.5 x floor)
#               (compare_settled.py says why)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
PY=/usr/bin/python3
BIN="$ROOT/build/pastemix"; REF=""; WORK="${TMPDIR:-/tmp}/pastemix_sortcheck"; CASES="pour bed case3"; MASS=0.2
LAB_H5="$ROOT/out/lab/lab.h5"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --bin) BIN="$2"; shift 2 ;;
    --ref) REF="$(realpath "$2")"; shift 2 ;;
    --work) WORK="$2"; shift 2 ;;
    --cases) CASES="$2"; shift 2 ;;
    --case3-mass) MASS="$2"; shift 2 ;;
    --lab-h5) LAB_H5="$2"; shift 2 ;;
    -h|--help) sed -n 2,19p "$0"; exit 0 ;;
    *) echo "sort_check: unknown option $1" >&2; exit 2 ;;
  esac
done
[[ -x "$BIN" ]] || { echo "sort_check: $BIN is not an executable" >&2; exit 2; }
BIN="$(realpath "$BIN")"
export OMP_WAIT_POLICY=passive OMP_NUM_THREADS=1
mkdir -p "$WORK"
SCENES="$WORK/scenes"
mkdir -p "$SCENES"
if [[ ! -f "$SCENES/pour.csv" ]]; then
  "$PY" "$ROOT/bench/tools/make_pour.py" "$SCENES/pour" >/dev/null
  "$PY" "$ROOT/bench/tools/csv_to_state.py" "$ROOT/bench/data/bed.csv.gz" "$SCENES/bed" >/dev/null
fi
for s in pour bed; do
  [[ -f "$SCENES/$s.toml" ]] || "$PY" "$ROOT/bench/tools/make_scene.py" "$ROOT/bench/scenes/$s.toml" \
      "$SCENES/$s.csv" "$SCENES/$s.toml" --dt 1e-5 --steps 2000 --skin 5e-4 --rolling cdt >/dev/null
done

run() {  # case variant extra-args... (variant "unsorted" and "sorted16" run OLD, with --ref)
  local c="$1" v="$2" out="$WORK/$1_$2"; shift 2
  local bin="$BIN"
  [[ -n "$REF" && $v != sorted ]] && bin="$REF"
  rm -rf "$out"; mkdir -p "$out"
  local args
  case "$c" in
    pour|bed) args=("$SCENES/$c.toml") ;;
    case3) args=("$ROOT/datasets/scenes/mixing_case3.toml" --overrides "$ROOT/datasets/scenes/mixing_fast.overrides.toml"
                 --set "factory.0.mass=$MASS") ;;
  esac
  (cd "$ROOT" && "$bin" run "${args[@]}" --threads 1 --quiet --out "$out" "$@") > "$out.log" 2>&1 \
      || { echo "$c ($v): run failed, see $out.log" >&2; return 1; }
  grep -m1 "stage profile" "$out.log" >&2 || true
  ls "$out"/*.h5 | head -1
}

failed=0
for c in $CASES; do
  t0=$(date +%s)
  a=$(run "$c" sorted)
  if [[ -n "$REF" ]]; then
    b=$(run "$c" unsorted)
    echo "== $c: $BIN vs $REF (both default)"
  else
    b=$(run "$c" unsorted --sort-every 0)
    echo "== $c: sorted (default) vs --sort-every 0"
  fi
  [[ $c == case3 ]] && run "$c" sorted16 --sort-every 16 >/dev/null
  if [[ $c == case3 ]]; then
    for v in sorted unsorted sorted16; do
      h5=$(ls "$WORK/${c}_$v"/*.h5 | head -1)
      "$BIN" maps "$h5" --lab 3 --lab-h5 "$LAB_H5" --out "$WORK/${c}_${v}_maps" > "$WORK/${c}_${v}_maps.log" 2>&1 \
          || { echo "case3: maps failed, see $WORK/${c}_${v}_maps.log" >&2; failed=1; continue 2; }
      grep -m1 "stop:\|at rest" "$WORK/${c}_$v.log" || true
    done
    # The floor against the first map: with --ref OLD's own round-off (OLD default against OLD sorted every 16th).
    first=sorted second=unsorted
    [[ -n "$REF" ]] && first=unsorted second=sorted
    "$PY" "$ROOT/scripts/compare_settled.py" maps "$WORK/${c}_${first}_maps/maps.h5" "$WORK/${c}_${second}_maps/maps.h5" \
        "$WORK/${c}_sorted16_maps/maps.h5" || failed=1
  else
    "$PY" "$ROOT/scripts/compare_settled.py" state "$a" "$b" || failed=1
  fi
  echo "($(( $(date +%s) - t0 )) s)"
done
[[ $failed -eq 0 ]] && echo "sort_check: all cases within tolerance" || echo "sort_check: SOME CASES OUT OF TOLERANCE"
exit $failed
