#!/usr/bin/env bash
# The main job on a fresh Debian machine: install what is missing, build, and run the pipeline on the
# shipped data: lab reduction -> parameters -> the chapter-3 case 3 scene (75 % paste, measured rheology)
# -> mixing maps -> score against the lab's block grid. Outputs go to out/ (override with OUT=...);
# out/summary.txt holds the short text summary.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-out}
threads=${THREADS:-$(nproc)}
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
scripts/install-deps.sh
scripts/build.sh
px=build/pastemix
start=$(date +%s%N)
stamp() { awk -v ns="$(($(date +%s%N) - start))" 'BEGIN { printf "%.1f", ns / 1e9 }'; }

# 1. Lab data -> parameters (parameters.toml, lab.h5, PNGs) and the drag-curve fit. The unmeasured 70 / 72.5 %
#    pastes come from the rheology model with its shape parameter calibrated on case 2 (issue 15, protocol
#    docs/rheology_protocol.md; the record docs/studies/rheology_case2/, an "at-rest effective" rheology).
mkdir -p "$out"
$px lab reduce datasets/thesis --out "$out/lab" \
  --rheology-calibration docs/studies/rheology_case2/rheology_calibration.toml > "$out/lab_reduce.log" 2>&1 ||
  { cat "$out/lab_reduce.log"; exit 1; }
$px lab drag-fit datasets/thesis --out "$out/drag" > "$out/drag.log" 2>&1 || { cat "$out/drag.log"; exit 1; }
t_lab=$(stamp)

# 2. Case 3 (75 % paste) with the measured yield stress and density from the parameter store, twice, side by
#    side: "at rest" (the shipped scene at the step of the case-3 time-step study, mixing_fast.overrides.toml)
#    and "flow" (the paste moving, with the frozen numerics of mixing_flow.overrides.toml, issue 22). Each run
#    gets half the threads: results do not depend on the thread count, and the flow pass runs mostly on one
#    thread, so two one-thread runs side by side end sooner than one two-thread run after the other.
tau=$($px lab param "$out/lab/parameters.toml" paste.yield_stress)
rho=$($px lab param "$out/lab/parameters.toml" paste.density)
each=$(( threads / 2 > 0 ? threads / 2 : 1 ))
run_case3() {  # OUTDIR OVERRIDES: the scene ends when its rock is at rest ([stop] in the scene, model/stop_rule.h)
  mkdir -p "$1"
  $px run datasets/scenes/mixing_case3.toml --overrides "$2" --set "fluid.0.yield_stress=$tau" \
    --set "fluid.0.density=$rho" --threads "$each" --quiet --out "$1" > "$1/run.log" 2>&1
}
echo "case 3: at rest and with flow, side by side ($each thread(s) each); logs in $out/case3/run.log, $out/case3_flow/run.log"
run_case3 "$out/case3" datasets/scenes/mixing_fast.overrides.toml & rest_pid=$!
run_case3 "$out/case3_flow" datasets/scenes/mixing_flow.overrides.toml & flow_pid=$!
ok=1
wait "$rest_pid" || { tail -20 "$out/case3/run.log"; ok=0; }
wait "$flow_pid" || { tail -20 "$out/case3_flow/run.log"; ok=0; }
((ok)) || exit 1
t_run=$(stamp)

# 3. Mixing maps and the score against the lab's case-3 grid (Table 3.2), for both runs (a flow result's maps
#    read its paste field: analysis/maps/paste_field.h).
for d in case3 case3_flow; do
  $px maps "$out/$d/mixing_case3.h5" --lab 3 --lab-h5 "$out/lab/lab.h5" --out "$out/$d/maps" > "$out/$d/maps.txt"
  $px score "$out/$d/mixing_case3.h5" --lab 3 --lab-h5 "$out/lab/lab.h5" --out "$out/$d/score" > "$out/$d/score.txt"
done
t_all=$(stamp)

summary_of() {  # DIR TITLE
  echo "== case 3, $2"
  grep -E "^stop: |^WARNING: end_time" "$out/$1/run.log" || true
  grep -E "^  total wall" "$out/$1/run.log" || true
  sed -n '/^HEADLINE/,/^mean absolute C error/p' "$out/$1/score.txt"
  grep -E "^S values|^S classes|^rock: poured" "$out/$1/score.txt"
}
{
  echo "pastemix main job ($(git rev-parse --short HEAD 2>/dev/null || echo unknown), $(date -u +%FT%TZ), $threads threads)"
  echo "lab: paste yield stress $tau Pa, density $rho kg/m3 (out/lab/parameters.toml); drag curve: out/drag/"
  summary_of case3 "the paste at rest (datasets/scenes/mixing_fast.overrides.toml)"
  summary_of case3_flow "the paste moving (dynamics = flow, datasets/scenes/mixing_flow.overrides.toml)"
  echo "times: lab ${t_lab} s, case-3 simulations (both, side by side) $(awk -v a="$t_run" -v b="$t_lab" 'BEGIN{printf "%.1f", a-b}') s, total ${t_all} s"
  echo "outputs: $out/lab/*.png, $out/drag/*.png, $out/case3{,_flow}/mixing_case3.h5 (+ .xmf for ParaView), $out/case3{,_flow}/score/*.png"
} | tee "$out/summary.txt"
echo "main job: done in ${t_all} s; outputs in $out/"
