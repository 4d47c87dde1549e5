#!/usr/bin/env bash
# Issue 21: blind predictions of the chapter-5 falling-height test (datasets/thesis repose_angle_tests.csv rows
# 2-4: 300.5 g of 0.315-8 mm rock, mu_r 0.16, released from the closed funnel at H_F = 6, 10.5 and 15.5 cm above
# the table). Their measured angles are reserved for blind validation: these runs are predictions, not compared
# with anything here. Settings, as the chapter-5 studies chose them (docs/studies/repose_ch5/README.md): the PSD
# cut at 3.35 mm (3.35-5.0 / 5.0-8.0 mm: 0.4127 / 0.0391 renormalised), dt 1.37e-5 s (20 % of the Rayleigh time
# of a 3.35 mm sphere at E = 4.68e7 Pa, the chapter-5 stiffness study's choice). ASSUMED geometry: the funnel of
# repose_ch5.toml held still with its tube's bottom (and the plate) at H_F; the plate out at 0.02 s; 3 s in all
# (the discharge, then settling). 3 seeds each (the same seeds at every height); final piles kept for
# `pastemix repose` (angle and pile diameter).
# Floor: at 10.5 and 15.5 cm every seed of the first runs had a sphere roll off the scene's 0.8 m domain
# (0.17-1.12 m/s along the floor at 0.47-0.71 s; ledger rows kept as failed), which stopped the run. A sphere
# rolling at 1.1 m/s against the constant rolling torque (decelerating ~(5/7) mu_r g = 1.1 m/s2) comes to rest
# within ~0.55 m, so there the floor is 2 m x 2 m (domain +-1 m; the pile-angle fit keeps to the pile). At
# 15.5 cm seed 2 still reached x = 1 m at 1.36 s (0.21 m/s), so there it is 4 m x 4 m (+-2 m). The lab's table
# size is not stated. The domain decides nothing else (the neighbour grid spans the particles, not the domain):
# a run in which no sphere reaches the smaller edge is the same run bit for bit.
#   docs/studies/rolling_t61/falling_height.sh 6|10.5|15.5 [--jobs N | --mpi]
set -euo pipefail
pm=${PASTEMIX:-build/pastemix}
here=docs/studies/rolling_t61
h_cm=${1:?the falling height, cm: 6, 10.5 or 15.5}
shift
h=$(awk -v c="$h_cm" 'BEGIN { printf "%.4f", c / 100 }')
zx=$(awk -v c="$h_cm" 'BEGIN { printf "%.4f", c / 100 + 0.02 }')  # the cone's bottom: the 2 cm tube above H_F
floor=()
case $h_cm in
  10.5) floor=(--set "domain.min=[-1.0, -1.0, -0.01]" "domain.max=[1.0, 1.0, 0.3]") ;;
  15.5) floor=(--set "domain.min=[-2.0, -2.0, -0.01]" "domain.max=[2.0, 2.0, 0.3]") ;;
esac
psd='factory.0.psd=[{d_min = 3.35e-3, d_max = 5.0e-3, fraction = 0.91346}, {d_min = 5.0e-3, d_max = 8.0e-3, fraction = 0.08654}]'
exec "$pm" sweep datasets/scenes/repose_ch5.toml --vary dt --values 1.37e-5 --seeds 3 \
  --set "$psd" "wall.funnel.z_exit=$zx" "wall.funnel.velocity=[0, 0, 0]" "wall.plate.center=[0, 0, $h]" end_time=3 "${floor[@]}" \
  --qoi repose_angle --checkpoint-every 300 --out "out/studies/falling_height/h$h_cm" \
  --save "out/studies/falling_height/h$h_cm/piles" --ledger "$here/falling_height_$h_cm.csv" "$@"
