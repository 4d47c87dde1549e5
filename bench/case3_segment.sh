#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Case 3 of the main job (mixing_case3 + mixing_fast overrides, the store's tau_y and density) timed over a
# segment that starts from a checkpoint, so that a build is timed on the phase it is slow in (the rock in
# the paste) without the minutes before it. Used by issue 19's fluid-pass work (bench/README.md).
#   bench/case3_segment.sh [--at 1.5] [--length 0.3] [--threads 2] [--repeats 2] [--work DIR]
#                          [--make-bin BIN] BIN...
# The first call runs --make-bin (default: the first BIN) from t = 0 to --at and keeps the checkpoint written
# there (in DIR, reused by later calls with the same --at and --length); then each BIN resumes it to
# --at + --length, interleaved, --repeats times. It prints, per run, the segment's loop time, s per simulated
# second and its own stage profile (the resumed run's minus the one stored in the checkpoint), and writes
# the results in DIR/seg_<k>_<repeat>/. The scene is a copy of mixing_case3.toml with [output]
# checkpoint_interval = --at (overrides only replace existing keys), so its checkpoint is of that copy.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
AT=1.5; LEN=0.3; THREADS=2; REPEATS=2; WORK=${TMPDIR:-/tmp}/pastemix_case3_segment; MAKE=""; BINS=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --at) AT="$2"; shift 2 ;;
    --length) LEN="$2"; shift 2 ;;
    --threads) THREADS="$2"; shift 2 ;;
    --repeats) REPEATS="$2"; shift 2 ;;
    --work) WORK="$2"; shift 2 ;;
    --make-bin) MAKE="$2"; shift 2 ;;
    -h|--help) sed -n 2,14p "$0"; exit 0 ;;
    -*) echo "case3_segment: unknown option $1" >&2; exit 2 ;;
    *) BINS+=("$1"); shift ;;
  esac
done
[[ ${#BINS[@]} -gt 0 ]] || { echo "case3_segment: name at least one pastemix binary" >&2; exit 2; }
for b in "${BINS[@]}" ${MAKE:+"$MAKE"}; do [[ -x "$b" ]] || { echo "case3_segment: $b is not an executable" >&2; exit 2; }; done
MAKE=${MAKE:-${BINS[0]}}
S="$ROOT/datasets/scenes"
TAU=137.97137433825228; RHO=1843   # the main job's store values (out/lab/parameters.toml of the shipped data)
END=$(awk -v a="$AT" -v l="$LEN" 'BEGIN { printf "%.6g", a + l }')
mkdir -p "$WORK"
SCENE="$WORK/case3_at$AT.toml"
grep -q '^interval = 0.1 ' "$S/mixing_case3.toml" || { echo "case3_segment: mixing_case3.toml's [output] interval line changed" >&2; exit 2; }
sed "s/^interval = 0.1 .*/interval = 0.1\ncheckpoint_interval = $AT/" "$S/mixing_case3.toml" > "$SCENE"
args=("$SCENE" --overrides "$S/mixing_fast.overrides.toml" --set "fluid.0.yield_stress=$TAU" --set "fluid.0.density=$RHO"
      --set "end_time=$END" --threads "$THREADS" --quiet)
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} OMP_NUM_THREADS=$THREADS
CK="$WORK/checkpoint_at${AT}_len$LEN.h5"
if [[ ! -f "$CK" ]]; then
  echo "case3_segment: making the checkpoint at t = $AT s with $MAKE (minutes)"
  rm -rf "$WORK/make"; mkdir -p "$WORK/make"
  "$MAKE" run "${args[@]}" --out "$WORK/make" > "$WORK/make/run.log" 2>&1 &
  pid=$!
  stem=$(basename "$SCENE" .toml)
  while kill -0 $pid 2>/dev/null; do
    if [[ -f "$WORK/make/$stem.checkpoint.h5" ]]; then sleep 2; cp "$WORK/make/$stem.checkpoint.h5" "$CK.part"; kill $pid; break; fi
    sleep 2
  done
  wait $pid 2>/dev/null || true
  [[ -f "$CK.part" ]] || { echo "case3_segment: no checkpoint was written (see $WORK/make/run.log)" >&2; exit 3; }
  mv "$CK.part" "$CK"
fi
for ((r = 1; r <= REPEATS; r++)); do
  for k in "${!BINS[@]}"; do
    d="$WORK/seg_${k}_$r"; rm -rf "$d"; mkdir -p "$d"
    cp "$CK" "$d/$(basename "$SCENE" .toml).checkpoint.h5"
    "${BINS[$k]}" run "${args[@]}" --out "$d" --resume "$d" > "$d/run.log" 2>&1 \
      || { echo "case3_segment: ${BINS[$k]} failed, see $d/run.log" >&2; exit 3; }
    /usr/bin/python3 "$ROOT/bench/tools/segment_profile.py" "$CK" "$d/run.log" "$LEN" "bin $k (${BINS[$k]}) run $r"
  done
done
