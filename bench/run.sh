#!/usr/bin/env bash
# pastemix vs LIGGGHTS 3.8 benchmark: same scenes, same initial particles, same dt and skin.
# Prints particle-steps/s for both codes and their ratio, the 2-thread speed-up of each and their peak memory per
# particle, all measured in one run, and writes bench/results/<UTC date>-<rolling>.csv.
#
#   bench/run.sh [--scenes "pour bed"] [--threads "1 2"] [--repeats 3] [--steps-pour 2000]
#                [--steps-bed 2000] [--dt 1e-5] [--skin 5e-4] [--rolling "cdt off"]
#                [--scaling "1 2 4"] [--wait passive|active] [--liggghts-only] [--resettle]
#
# --rolling: one or more of cdt, epsd2, off (default "cdt off": the thesis's law, and both codes without
# rolling resistance, where they have exactly the same physics), interleaved in the same run.
# --scaling "K ...": also the pour at K^2 x 12,960 spheres (K = 1 2 4: 13k, 52k, 207k), 1 thread, both codes:
# cost per particle-step, its growth and exponent, peak memory per particle (tools/scaling.py).
# Environment: PASTEMIX=path/to/pastemix (default build/pastemix, built with scripts/build.sh if missing).
#   PASTEMIX_BASELINE=path/to/other/pastemix: a third code, interleaved with the two (L P B L P B ...), for a
#   before/after comparison of two engine builds measured side by side in the same run.
# Installs the Debian package liggghts (and its Open MPI launcher) when the liggghts binary is missing.
set -euo pipefail
BENCH="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$BENCH/.." && pwd)"
PY=/usr/bin/python3   # has numpy; the python3 first on PATH may not

SCENES="pour bed"; THREADS="1 2"; REPEATS=3; STEPS_POUR=2000; STEPS_BED=2000; ROLLINGS="cdt off"; SCALING=""
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
    --rolling) ROLLINGS="$2"; shift 2 ;;
    --scaling) SCALING="$2"; shift 2 ;;
    --dt) DT="$2"; shift 2 ;;
    --skin) SKIN="$2"; shift 2 ;;
    --wait) WAIT="$2"; shift 2 ;;
    --liggghts-only) LIGGGHTS_ONLY=1; shift ;;
    --resettle) RESETTLE=1; shift ;;
    -h|--help) sed -n 2,17p "$0"; exit 0 ;;
    *) echo "run.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
case "$WAIT" in passive|active) ;; *) echo "run.sh: --wait must be passive or active" >&2; exit 2 ;; esac
for r in $ROLLINGS; do
  case "$r" in cdt|epsd2|off) ;; *) echo "run.sh: --rolling takes cdt, epsd2 and/or off (got $r)" >&2; exit 2 ;; esac
done
[[ -n "$ROLLINGS" ]] || { echo "run.sh: --rolling needs at least one law" >&2; exit 2; }
for k in $SCALING; do
  [[ "$k" =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: --scaling takes positive integers (got $k)" >&2; exit 2; }
done
ROLLING="${ROLLINGS%% *}"   # the first law settles the bed (--resettle) and runs the scaling series

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

# The state of the vCPUs before and after the runs (bench/vcpu_probe: each CPU's random-read, latency and
# arithmetic rates, pinned there in turn): on the project's VMs one vCPU at times reads memory 2-4x slower than
# the other, which a ratio measured in those minutes carries. Kept in bench/results/<stamp>-vcpu.txt.
VCPU_PROBE="$ROOT/build/pastemix_vcpu_probe"
[[ -x "$VCPU_PROBE" ]] || cmake --build "$ROOT/build" --target pastemix_vcpu_probe >&2 || true
vcpu_state() {  # label
  if [[ -x "$VCPU_PROBE" ]]; then
    { echo "# $1 ($(date -u +%H:%M:%S) UTC)"; "$VCPU_PROBE"; } | tee -a "$BENCH/results/$STAMP-vcpu.txt" >&2
  else
    echo "run.sh: no $VCPU_PROBE: the vCPUs' state is not recorded" >&2
  fi
}
vcpu_state "before the runs"

CPUTIME=("$PY" "$BENCH/tools/cputime.py")

run_liggghts() {  # rolling|scaling scene threads tag steps [data input extra-vars...]
  # (tag: r<repeat>, or "setup" for the 1-step CPU baseline; data/input default to the scene's own)
  local dir="$WORK/$1" data="${6:-$STATES/$2.data}" input="${7:-$2}" rolling="$1"
  [[ $1 == scaling ]] && rolling="$ROLLING"   # the scaling series' folder; its law is the first one
  local log="$dir/liggghts_$2_t$3_$4.log"
  (cd "$dir" && "${CPUTIME[@]}" "$log.cpu" -- "${MPIRUN[@]}" -np "$3" liggghts -in "$BENCH/liggghts/in.$input" \
      -log none -var inc "$BENCH/liggghts" -var data "$data" -var rolling "$rolling" \
      -var dt "$DT" -var skin "$SKIN" -var steps "$5" "${@:8}") > "$log" 2>&1 \
      || { echo "LIGGGHTS failed, see $log" >&2; exit 1; }
  [[ $4 == setup ]] || grep -m1 "Loop time" "$log" >&2
}

if [[ $LIGGGHTS_ONLY -eq 0 ]]; then
  # The pastemix scenes: bench/scenes/<scene>.toml + the same particles, dt, skin and rolling law; and a
  # 1-step copy for the CPU-time baseline (setup: TOML parsing, overlap checks, output files).
  for rolling in $ROLLINGS; do
    mkdir -p "$WORK/$rolling"
    for scene in $SCENES; do
      for tag in run setup; do
        steps=$(steps_of "$scene"); [[ $tag == setup ]] && steps=1
        "$PY" "$BENCH/tools/make_scene.py" "$BENCH/scenes/$scene.toml" "$STATES/$scene.csv" \
            "$WORK/$rolling/${scene}_$tag.toml" --dt "$DT" --steps "$steps" --skin "$SKIN" --rolling "$rolling"
      done
    done
  done
fi

run_engine() {  # code binary rolling scene threads tag [toml]   (code: pastemix or baseline)
  local code="$1" bin="$2"; shift 2
  local dir="$WORK/$1" log="$WORK/$1/${code}_$2_t$3_$4.log" out="$WORK/$1/out_${code}_$2_t$3_$4"
  local toml="${5:-$WORK/$1/$2_run.toml}"
  [[ $4 == setup ]] && toml="$WORK/$1/$2_setup.toml"
  mkdir -p "$out"
  (cd "$dir" && OMP_NUM_THREADS="$3" "${CPUTIME[@]}" "$log.cpu" -- "$bin" run "$toml" --threads "$3" \
      --quiet --out "$out") > "$log" 2>&1 || { echo "$code ($bin) failed, see $log" >&2; exit 1; }
  # Keep the first repeat's output (report.py compares its final state with LIGGGHTS'); drop the rest.
  [[ $4 == r1 ]] || rm -rf "$out"
  [[ $4 == setup ]] || grep -m1 "total wall" "$log" >&2
}
BASELINE="${PASTEMIX_BASELINE:-}"
if [[ -n "$BASELINE" && ! -x "$BASELINE" ]]; then
  echo "run.sh: PASTEMIX_BASELINE=$BASELINE is not an executable" >&2; exit 2
fi
# The runs start inside their work folders: a relative path given in the environment must not break them.
[[ $LIGGGHTS_ONLY -eq 1 ]] || PASTEMIX="$(realpath "$PASTEMIX")"
[[ -z "$BASELINE" ]] || BASELINE="$(realpath "$BASELINE")"
run_pastemix() {  # rolling scene threads tag [toml]: pastemix, then the baseline build if there is one
  run_engine pastemix "$PASTEMIX" "$@"
  [[ -z "$BASELINE" ]] || run_engine baseline "$BASELINE" "$@"
}

# Interleave the two codes (L P L P ...) and the rolling laws so slow phases of a noisy machine hit all alike.
for scene in $SCENES; do
  for t in $THREADS; do
    for rolling in $ROLLINGS; do
      run_liggghts "$rolling" "$scene" "$t" setup 1
      [[ $LIGGGHTS_ONLY -eq 1 ]] || run_pastemix "$rolling" "$scene" "$t" setup
    done
    for ((r = 1; r <= REPEATS; r++)); do
      for rolling in $ROLLINGS; do
        echo "== $scene, $t thread(s), rolling $rolling, repeat $r/$REPEATS" >&2
        run_liggghts "$rolling" "$scene" "$t" "r$r" "$(steps_of "$scene")"
        [[ $LIGGGHTS_ONLY -eq 1 ]] || run_pastemix "$rolling" "$scene" "$t" "r$r"
      done
    done
  done
done

# The scaling series: the pour K times wider and longer (K^2 x the spheres), 1 thread, rolling $ROLLING.
if [[ -n "$SCALING" ]]; then
  mkdir -p "$WORK/scaling"
  for k in $SCALING; do
    "$PY" "$BENCH/tools/make_pour.py" "$STATES/pour_s$k" --scale "$k" >&2
    bx=$("$PY" -c "print('%.9g' % (0.165 * $k))"); by=$("$PY" -c "print('%.9g' % (0.200 * $k))")
    if [[ $LIGGGHTS_ONLY -eq 0 ]]; then
      "$PY" "$BENCH/tools/make_scene.py" "$BENCH/scenes/pour.toml" "$STATES/pour_s$k.csv" \
          "$WORK/scaling/pours${k}_run.toml" --dt "$DT" --steps "$STEPS_POUR" --skin "$SKIN" --rolling "$ROLLING" \
          --box "$bx" "$by"
    fi
    for ((r = 1; r <= REPEATS; r++)); do
      echo "== scaling: pour x$((k * k)), 1 thread, repeat $r/$REPEATS" >&2
      run_liggghts scaling "pours$k" 1 "r$r" "$STEPS_POUR" "$STATES/pour_s$k.data" pour \
          -var boxx "$bx" -var boxy "$by"
      [[ $LIGGGHTS_ONLY -eq 1 ]] || run_pastemix scaling "pours$k" 1 "r$r" "$WORK/scaling/pours${k}_run.toml"
    done
  done
fi

vcpu_state "after the runs"
liggghts_version="$(command -v liggghts) (Debian $(dpkg-query -W -f '${Version}' liggghts 2>/dev/null))"
: > "$WORK/table.txt"
for rolling in $ROLLINGS; do
  export BENCH_SETTINGS="dt $DT s; skin $SKIN m; rolling $rolling; wait $WAIT; steps pour $STEPS_POUR bed $STEPS_BED;\
 repeats $REPEATS; pastemix $PASTEMIX;${BASELINE:+ baseline $BASELINE;} liggghts $liggghts_version"
  echo -e "\n######## rolling $rolling\nsettings: $BENCH_SETTINGS" | tee -a "$WORK/table.txt"
  "$PY" "$BENCH/tools/report.py" "$WORK/$rolling" "$BENCH/results/$STAMP-$rolling.csv" | tee -a "$WORK/table.txt"
done
if [[ -n "$SCALING" ]]; then
  export BENCH_SETTINGS="scaling series; dt $DT s; skin $SKIN m; rolling $ROLLING; wait $WAIT; steps $STEPS_POUR;\
 repeats $REPEATS; pastemix $PASTEMIX; liggghts $liggghts_version"
  echo -e "\n######## scaling series (pour, 1 thread, rolling $ROLLING)" | tee -a "$WORK/table.txt"
  "$PY" "$BENCH/tools/scaling.py" "$WORK/scaling" "$BENCH/results/$STAMP-scaling.csv" | tee -a "$WORK/table.txt"
fi
[[ -f "$BENCH/results/$STAMP-vcpu.txt" ]] &&
  echo -e "\n######## the vCPUs (bench/vcpu_probe)" | cat - "$BENCH/results/$STAMP-vcpu.txt" | tee -a "$WORK/table.txt"
echo "all tables: $WORK/table.txt" >&2
