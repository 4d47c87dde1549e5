#!/usr/bin/env bash
# The measured cost per run of each point of the three studies, at one seed, on a SHORT run (end_time 0.06 s:
# the plate out at 0.02 s and 0.04 s of discharge; a full run is 6-9 s): particles, particle-steps, wall
# seconds of the step loop, one thread. The full run's cost is then its particle-steps (particles x
# end_time / dt) at the measured rate. Run from the repository root; writes out/studies/cost/<study>_<v>.log.
set -euo pipefail
pm=${PASTEMIX:-build/pastemix}
scene=datasets/scenes/repose_ch5.toml
t61=datasets/scenes/repose_t61
mkdir -p out/studies/cost
export OMP_NUM_THREADS=1
short=(--qoi final_height --set end_time=0.06 --no-cache --tol 1)
for v in 0.04 0.02 0.01; do
  "$pm" sweep "$scene" --overrides $t61/dmax3.35.overrides.toml --vary lift_speed --values $v --settle 0 "${short[@]}" \
    --out out/studies/cost/lift_$v > out/studies/cost/lift_$v.log 2>&1
done
for v in 3.35e-3 0; do
  "$pm" sweep "$scene" --overrides $t61/dmax5.0.overrides.toml --vary psd_cut --values $v "${short[@]}" \
    --out out/studies/cost/cut_$v > out/studies/cost/cut_$v.log 2>&1
done
for v in 4.68e6 4.68e7 4.68e8; do
  "$pm" sweep "$scene" --overrides $t61/dmax3.35.overrides.toml --vary youngs_modulus --material rock --values $v \
    "${short[@]}" --out out/studies/cost/E_$v > out/studies/cost/E_$v.log 2>&1
done
grep -h " seed " out/studies/cost/*.log
