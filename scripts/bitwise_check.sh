#!/usr/bin/env bash
# Bit-for-bit check of an engine change: runs short versions of the bench scenes, mixing case 3 and the
# chapter-7 test-3 start with a reference binary (built from the code before the change) and with the new
# one, and compares the result files bitwise (scripts/compare_states.py: every dataset and attribute except
# the wall-clock profile). Exit 0 when every case is identical, 1 otherwise.
#
#   scripts/bitwise_check.sh --ref /path/to/old/pastemix [--new build/pastemix] [--work DIR]
#                            [--cases "pour_cdt bed_cdt ..."] [--case3-end 0.35] [--new-args "..."]
#
# --new-args: extra `pastemix run` arguments for the new binary only, e.g. "--sort-every 0" (the spatial
# sort of the particle store changes the order of force sums, so a check against a binary from before it
# runs the new one with the sort off).
# The reference outputs are kept in DIR/ref-<sha1 of the reference binary>/ and reused by later calls.
# Cases (each a few seconds to ~1 min on one core of the project machine):
#   pour_cdt, pour_cdt_t2   bench pour, 400 steps, constant-torque rolling, 1 / 2 threads
#   pour_off                bench pour, 400 steps, no rolling resistance
#   bed_cdt, bed_cdt_t2     bench settled bed, 300 steps, constant torque, 1 / 2 threads
#   bed_epsd2               bench bed, 300 steps, elastic-plastic rolling (rolling spring history)
#   case3_t1, case3_t2      mixing_case3 + mixing_fast overrides to end_time = --case3-end (s), 1 / 2 threads
#   ch7t3                   pour_ch7_test3 + pour_ch7_fast overrides, first 0.05 s
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
PY=/usr/bin/python3
REF=""; NEW="$ROOT/build/pastemix"; WORK="${TMPDIR:-/tmp}/pastemix_bitwise"; CASE3_END=0.35; NEW_ARGS=""
CASES="pour_cdt pour_cdt_t2 pour_off bed_cdt bed_cdt_t2 bed_epsd2 case3_t1 case3_t2 ch7t3"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --ref) REF="$2"; shift 2 ;;
    --new) NEW="$2"; shift 2 ;;
    --work) WORK="$2"; shift 2 ;;
    --cases) CASES="$2"; shift 2 ;;
    --case3-end) CASE3_END="$2"; shift 2 ;;
    --new-args) NEW_ARGS="$2"; shift 2 ;;
    -h|--help) sed -n 2,21p "$0"; exit 0 ;;
    *) echo "bitwise_check: unknown option $1" >&2; exit 2 ;;
  esac
done
[[ -x "$REF" ]] || { echo "bitwise_check: --ref must name an executable pastemix (the build before the change)" >&2; exit 2; }
[[ -x "$NEW" ]] || { echo "bitwise_check: $NEW is not an executable" >&2; exit 2; }
export OMP_WAIT_POLICY=passive
REF_DIR="$WORK/ref-$(sha1sum "$REF" | cut -c1-12)"
SCENES="$WORK/scenes"
mkdir -p "$REF_DIR" "$SCENES" "$WORK/new"

# Bench scenes: the shared initial particles (bench/tools), few steps.
if [[ ! -f "$SCENES/pour.csv" ]]; then
  "$PY" "$ROOT/bench/tools/make_pour.py" "$SCENES/pour" >/dev/null
  "$PY" "$ROOT/bench/tools/csv_to_state.py" "$ROOT/bench/data/bed.csv.gz" "$SCENES/bed" >/dev/null
fi
bench_scene() {  # name template steps rolling
  [[ -f "$SCENES/$1.toml" ]] || "$PY" "$ROOT/bench/tools/make_scene.py" "$ROOT/bench/scenes/$2.toml" \
      "$SCENES/$2.csv" "$SCENES/$1.toml" --dt 1e-5 --steps "$3" --skin 5e-4 --rolling "$4" >/dev/null
}
bench_scene pour_cdt pour 400 cdt
bench_scene pour_off pour 400 off
bench_scene bed_cdt bed 300 cdt
bench_scene bed_epsd2 bed 300 epsd2

# args_of CASE -> the pastemix run arguments (scene first); threads_of CASE -> thread count.
args_of() {
  local s="$ROOT/datasets/scenes"
  case "$1" in
    pour_cdt|pour_cdt_t2) echo "$SCENES/pour_cdt.toml" ;;
    pour_off) echo "$SCENES/pour_off.toml" ;;
    bed_cdt|bed_cdt_t2) echo "$SCENES/bed_cdt.toml" ;;
    bed_epsd2) echo "$SCENES/bed_epsd2.toml" ;;
    case3_t1|case3_t2) echo "$s/mixing_case3.toml --overrides $s/mixing_fast.overrides.toml --set end_time=$CASE3_END" ;;
    ch7t3) echo "$s/pour_ch7_test3.toml --overrides $s/pour_ch7_fast.overrides.toml --set end_time=0.05" ;;
    *) echo "bitwise_check: unknown case $1" >&2; exit 2 ;;
  esac
}
threads_of() { [[ $1 == *_t2 ]] && echo 2 || echo 1; }

run_case() {  # binary case outdir [extra args]
  local out="$3/$2"
  rm -rf "$out"; mkdir -p "$out"
  # shellcheck disable=SC2046,SC2086
  (cd "$ROOT" && OMP_NUM_THREADS="$(threads_of "$2")" "$1" run $(args_of "$2") --threads "$(threads_of "$2")" \
      --quiet --out "$out" ${4:-}) > "$out.log" 2>&1 || { echo "$2: run failed ($1), see $out.log" >&2; return 1; }
  ls "$out"/*.h5 | head -1
}

failed=0
for c in $CASES; do
  t0=$(date +%s)
  ref_h5=$(ls "$REF_DIR/$c"/*.h5 2>/dev/null | head -1 || true)
  [[ -n "$ref_h5" ]] || ref_h5=$(run_case "$REF" "$c" "$REF_DIR")
  new_h5=$(run_case "$NEW" "$c" "$WORK/new" "$NEW_ARGS")
  verdict=$("$PY" "$ROOT/scripts/compare_states.py" "$ref_h5" "$new_h5") || failed=1
  printf '%-12s %-60s (%ds)\n' "$c" "$verdict" "$(( $(date +%s) - t0 ))"
done
[[ $failed -eq 0 ]] && echo "bitwise_check: all cases identical" || echo "bitwise_check: SOME CASES DIFFER"
exit $failed
