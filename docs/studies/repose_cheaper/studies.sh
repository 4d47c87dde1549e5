#!/usr/bin/env bash
# The "cheaper study" sweeps of issue 21, ready to run (each a study of keyed tasks: resumable, with its
# committed ledger beside this file). Run from the repository root:
#   docs/studies/repose_cheaper/studies.sh lift_speed|psd_cut|youngs [EXTRA ARGS, e.g. --jobs 2, --mpi, --task-index N]
# Under MPI: mpirun -np K docs/studies/repose_cheaper/studies.sh lift_speed (PASTEMIX=build/pastemix).
# Choice rule (stated before the runs): the cheapest setting whose mean angle lies within the seed spread of
# the reference's, i.e. --tol 0.04 (1.5 deg seed sd / ~36 deg), 3 seeds per point (common random numbers).
set -euo pipefail
pm=${PASTEMIX:-build/pastemix}
scene=datasets/scenes/repose_ch5.toml
here=docs/studies/repose_cheaper
study=${1:?which study: lift_speed, psd_cut or youngs}
shift
common=(--qoi repose_angle --seeds 3 --tol 0.04 --checkpoint-every 600)
# The lift-speed study chose 0.04 m/s (lift_speed.txt, 2026-12-03): the cut and E studies run at it, with the
# end time that --settle 1 gives (the same lift height, then 1 s of settling; app/study/sweep.cpp set_lift_speed):
# d_max 3.35 mm set 0.02 + 4.98 x 0.01 / 0.04 + 1 = 2.265 s; d_max 5.0 mm set 0.02 + 7.98 x 0.01 / 0.04 + 1 = 3.015 s.
lift=(--set "wall.funnel.velocity=[0, 0, 0.04]")
case "$study" in
  lift_speed)  # d_max 3.35 mm set (Table 6.1), the thesis's 0.01 m/s (reference) against 0.02 and 0.04 m/s;
               # the lift covers the same height, the last 1 s of settling is kept (--settle 1)
    exec "$pm" sweep "$scene" --overrides datasets/scenes/repose_t61/dmax3.35.overrides.toml \
      --vary lift_speed --values 0.04 0.02 0.01 --settle 1 "${common[@]}" \
      --out out/studies/repose_lift_speed --ledger "$here/lift_speed.csv" "$@" ;;
  psd_cut)     # d_max 5.0 mm set: cut below 3.35 mm (its own step: dt follows the smallest sphere kept) against none
    exec "$pm" sweep "$scene" --overrides datasets/scenes/repose_t61/dmax5.0.overrides.toml \
      --vary psd_cut --values 3.35e-3 0 "${common[@]}" "${lift[@]}" --set end_time=3.015 \
      --out out/studies/repose_psd_cut --ledger "$here/psd_cut.csv" "$@" ;;
  youngs)      # d_max 3.35 mm set: E of the rock 4.68e6 / 4.68e7 (the thesis's reduced E) / 4.68e8 Pa, the step
               # scaled by sqrt(E0 / E) (the same fraction of the Rayleigh time)
    exec "$pm" sweep "$scene" --overrides datasets/scenes/repose_t61/dmax3.35.overrides.toml \
      --vary youngs_modulus --material rock --values 4.68e6 4.68e7 4.68e8 "${common[@]}" "${lift[@]}" --set end_time=2.265 \
      --out out/studies/repose_youngs --ledger "$here/youngs.csv" "$@" ;;
  *) echo "studies.sh: unknown study '$study' (lift_speed, psd_cut, youngs)" >&2; exit 2 ;;
esac
