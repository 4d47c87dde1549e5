#!/usr/bin/env bash
# pastemix vs LIGGGHTS 3.8 benchmark: same scenes, same initial particles, same dt and skin.
# Prints particle-steps/s for both codes and their ratio, and writes bench/results/<UTC date>.csv.
#
#   bench/run.sh [--scenes "pour bed"] [--threads "1 2"] [--repeats 3] [--steps-pour 2000]
#                [--steps-bed 2000] [--dt 1e-5] [--skin 5e-4] [--rolling cdt|epsd2|off]
#                [--wait passive|active] [--liggghts-only] [--resettle]
#
# Environment: PASTEMIX=path/to/pastemix (default build/pastemix, built with scripts/build.sh if missing).
# Installs the Debian package liggghts (and its Open MPI launcher) when the liggghts binary is missing.
set -euo pipefail
BENCH="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$BENCH/.." && pwd)"
PY=/usr/bin/python3   # has numpy; the python3 first on PATH may not

SCENES="pour bed"; THREADS="1 2"; REPEATS=3; STEPS_POUR=2000; STEPS_BED=2000; ROLLING=cdt
DT=1e-5; SKIN=5e-4   # s, m: the same in both codes
LIGGGHTS_ONLY=0; RESETTLE=0
# How idle threads/ranks wait. passive (default): OpenMP threads sleep (OMP_WAIT_POLICY=passive) and MPI ranks
# yield (mpi_yield_when_idle 1). On a shared, oversubscribed machine spinning waiters steal the cores the
# workers need and both codes slow down 2-4x at 2 threads; active = both spin, for a dedicated machine.
WAIT=passive
while [[ $# -gt 0 ]]; do
  case "$1" in
    --scenes) SCENES="$2"; shift 2 ;;
    --threads) THREADS="$2"; shift 2 ;;
    --repeats) REPEATS="$2"; shift 2 ;;
    --steps-pour) STEPS_POUR="$2"; shift 2 ;;
    --steps-bed) STEPS_BED="$2"; shift 2 ;;
    --rolling) ROLLING="$2"; shift 2 ;;
    --dt) DT="$2"; shift 2 ;;
    --skin) SKIN="$2"; shift 2 ;;
    --wait) WAIT="$2"; shift 2 ;;
    --liggghts-only) LIGGGHTS_ONLY=1; shift ;;
    --resettle) RESETTLE=1; shift ;;
    -h|--help) sed -n 2,12p "$0"; exit 0 ;;
    *) echo "run.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
case "$WAIT" in passive|active) ;; *) echo "run.sh: --wait must be passive or active" >&2; exit 2 ;; esac
case "$ROLLING" in cdt|epsd2|off) ;; *) echo "run.sh: --rolling must be cdt, epsd2 or off" >&2; exit 2 ;; esac

# --- LIGGGHTS and its MPI launcher (Debian: /usr/bin/liggghts, mpirun from openmpi-bin) ---------------
if ! command -v liggghts >/dev/null || ! command -v mpirun >/dev/null; then
  echo "run.sh: installing the Debian package liggghts (LIGGGHTS-PUBLIC 3.8.0) and Open MPI" >&2
  SUDO=""; [[ $EUID -ne 0 ]] && SUDO=sudo
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends liggghts openmpi-bin >&2
fi
MPIRUN=(mpirun --bind-to none)   # no pinning: pastemix's OpenMP threads are not pinned either
if [[ $WAIT == passive ]]; then MPIRUN+=(--mca mpi_yield_when_idle 1); else MPIRUN+=(--mca mpi_yield_when_idle 0); fi
export OMP_WAIT_POLICY="$WAIT"
[[ $EUID -eq 0 ]] && MPIRUN+=(--allow-run-as-root)

# --- pastemix ------------------------------------------------------------------------------------------
PASTEMIX="${PASTEMIX:-$ROOT/build/pastemix}"
if [[ $LIGGGHTS_ONLY -eq 0 && ! -x "$PASTEMIX" ]]; then
  echo "run.sh: building pastemix (scripts/build.sh)" >&2
  "$ROOT/scripts/build.sh" >&2
fi
if [[ $LIGGGHTS_ONLY -eq 0 ]] && ! "$PASTEMIX" run --help >/dev/null 2>&1; then
  echo "run.sh: $PASTEMIX has no 'run' command (engine not built in?): use --liggghts-only or PASTEMIX=..." >&2
  exit 2
fi

# --- initial states, generated once and read by both codes -------------------------------------------
STAMP="$(date -u +%Y-%m-%dT%H%M%SZ)"
WORK="$BENCH/work/$STAMP"
STATES="$BENCH/work/states"
mkdir -p "$WORK" "$STATES" "$BENCH/results"
"$PY" "$BENCH/tools/make_pour.py" "$STATES/pour" >&2
if [[ $RESETTLE -eq 1 || ! -f "$BENCH/data/bed.csv.gz" ]]; then
  echo "run.sh: settling the bed with LIGGGHTS (2 ranks; minutes)" >&2
  (cd "$WORK" && "${MPIRUN[@]}" -np 2 liggghts -in "$BENCH/liggghts/in.settle" -log settle.log \
      -var inc "$BENCH/liggghts" -var data "$STATES/pour.data" -var rolling "$ROLLING" \
      -var dt "$DT" -var skin "$SKIN" -var out "$WORK/bed.dump" -var ke_stop 1e-5 -var chunk 2000 >/dev/null)
  grep SETTLED "$WORK/settle.log" >&2
  "$PY" "$BENCH/tools/dump_to_state.py" "$WORK/bed.dump" "$STATES/bed" \
      "bed: pour settled by LIGGGHTS 3.8 (in.settle, rolling $ROLLING), released at rest" >&2
  gzip -9 -n -c "$STATES/bed.csv" > "$BENCH/data/bed.csv.gz"
else
  "$PY" "$BENCH/tools/csv_to_state.py" "$BENCH/data/bed.csv.gz" "$STATES/bed" >&2
fi

steps_of() { [[ $1 == pour ]] && echo "$STEPS_POUR" || echo "$STEPS_BED"; }

CPUTIME=("$PY" "$BENCH/tools/cputime.py")

run_liggghts() {  # scene threads tag steps   (tag: r<repeat>, or "setup" for the 1-step CPU baseline)
  local log="$WORK/liggghts_$1_t$2_$3.log"
  (cd "$WORK" && "${CPUTIME[@]}" "$log.cpu" -- "${MPIRUN[@]}" -np "$2" liggghts -in "$BENCH/liggghts/in.$1" \
      -log none -var inc "$BENCH/liggghts" -var data "$STATES/$1.data" -var rolling "$ROLLING" \
      -var dt "$DT" -var skin "$SKIN" -var steps "$4") > "$log" 2>&1 || { echo "LIGGGHTS failed, see $log" >&2; exit 1; }
  [[ $3 == setup ]] || grep -m1 "Loop time" "$log" >&2
}

if [[ $LIGGGHTS_ONLY -eq 0 ]]; then
  # The pastemix scenes: bench/scenes/<scene>.toml + the same particles, dt, skin and rolling law; and a
  # 1-step copy for the CPU-time baseline (setup: TOML parsing, overlap checks, output files).
  for scene in $SCENES; do
    for tag in run setup; do
      steps=$(steps_of "$scene"); [[ $tag == setup ]] && steps=1
      "$PY" "$BENCH/tools/make_scene.py" "$BENCH/scenes/$scene.toml" "$STATES/$scene.csv" \
          "$WORK/${scene}_$tag.toml" --dt "$DT" --steps "$steps" --skin "$SKIN" --rolling "$ROLLING"
    done
  done
fi

run_pastemix() {  # scene threads tag
  local log="$WORK/pastemix_$1_t$2_$3.log" out="$WORK/out_$1_t$2_$3" toml="$WORK/$1_run.toml"
  [[ $3 == setup ]] && toml="$WORK/$1_setup.toml"
  mkdir -p "$out"
  (cd "$WORK" && OMP_NUM_THREADS="$2" "${CPUTIME[@]}" "$log.cpu" -- "$PASTEMIX" run "$toml" --threads "$2" \
      --quiet --out "$out") > "$log" 2>&1 || { echo "pastemix failed, see $log" >&2; exit 1; }
  # Keep the first repeat's output (report.py compares its final state with LIGGGHTS'); drop the rest.
  [[ $3 == r1 ]] || rm -rf "$out"
  [[ $3 == setup ]] || grep -m1 "total wall" "$log" >&2
}

# Interleave the two codes (L P L P ...) so slow phases of a noisy machine hit both alike.
for scene in $SCENES; do
  for t in $THREADS; do
    run_liggghts "$scene" "$t" setup 1
    [[ $LIGGGHTS_ONLY -eq 1 ]] || run_pastemix "$scene" "$t" setup
    for ((r = 1; r <= REPEATS; r++)); do
      echo "== $scene, $t thread(s), repeat $r/$REPEATS" >&2
      run_liggghts "$scene" "$t" "r$r" "$(steps_of "$scene")"
      [[ $LIGGGHTS_ONLY -eq 1 ]] || run_pastemix "$scene" "$t" "r$r"
    done
  done
done

export BENCH_SETTINGS="dt $DT s; skin $SKIN m; rolling $ROLLING; wait $WAIT; steps pour $STEPS_POUR bed $STEPS_BED;\
 repeats $REPEATS; pastemix $PASTEMIX; liggghts $(command -v liggghts) (Debian $(dpkg-query -W -f '${Version}' liggghts 2>/dev/null))"
echo "settings: $BENCH_SETTINGS" | tee "$WORK/table.txt"
"$PY" "$BENCH/tools/report.py" "$WORK" "$BENCH/results/$STAMP.csv" | tee -a "$WORK/table.txt"
