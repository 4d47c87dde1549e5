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

# 2. Case 3 with the measured yield stress from the parameter store, at the time step chosen by the
#    case-3 time-step study (datasets/scenes/mixing_fast.overrides.toml).
tau=$($px lab param "$out/lab/parameters.toml" paste.yield_stress)
rho=$($px lab param "$out/lab/parameters.toml" paste.density)
mkdir -p "$out/case3"
# The scene ends when its rock is at rest ([stop] in the scene, model/stop_rule.h).
$px run datasets/scenes/mixing_case3.toml --overrides datasets/scenes/mixing_fast.overrides.toml \
  --set "fluid.0.yield_stress=$tau" --set "fluid.0.density=$rho" --threads "$threads" --out "$out/case3" \
  2>&1 | tee "$out/case3/run.log"
t_run=$(stamp)

# 3. Mixing maps and the score against the lab's case-3 grid (Table 3.2).
$px maps "$out/case3/mixing_case3.h5" --lab 3 --lab-h5 "$out/lab/lab.h5" --out "$out/case3/maps" > "$out/case3/maps.txt"
$px score "$out/case3/mixing_case3.h5" --lab 3 --lab-h5 "$out/lab/lab.h5" --out "$out/case3/score" \
  > "$out/case3/score.txt"
t_all=$(stamp)

{
  echo "pastemix main job ($(git rev-parse --short HEAD 2>/dev/null || echo unknown), $(date -u +%FT%TZ), $threads threads)"
  echo "lab: paste yield stress $tau Pa, density $rho kg/m3 (out/lab/parameters.toml); drag curve: out/drag/"
  grep -E "^stop: |^WARNING: end_time" "$out/case3/run.log" || true
  sed -n '/^HEADLINE/,/^mean absolute C error/p' "$out/case3/score.txt"
  grep -E "^rock: poured" "$out/case3/score.txt"
  echo "times: lab ${t_lab} s, case-3 simulation $(awk -v a="$t_run" -v b="$t_lab" 'BEGIN{printf "%.1f", a-b}') s, total ${t_all} s"
  echo "outputs: $out/lab/*.png, $out/drag/*.png, $out/case3/mixing_case3.h5 (+ .xmf for ParaView), $out/case3/score/*.png"
} | tee "$out/summary.txt"
echo "main job: done in ${t_all} s; outputs in $out/"
