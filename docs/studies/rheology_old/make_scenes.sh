#!/usr/bin/env bash
# The old assumed rheology of issue 15 (the scenes' headers before 7dd6c00: tau_y halved and eta_B / 1.5 per
# 2.5 points below the 75 % paste; density by the mixture rule scaled to the measured 1843 kg/m3), as scene
# files: each mixing scene of the frozen engine's tree with its `rheology_from` line replaced by the three
# numbers it carried before. Nothing else differs. Usage: make_scenes.sh SRC_TREE OUT_DIR
set -euo pipefail
src=$1 out=$2
mkdir -p "$out"
for c in 1 4 5 6 7; do
  case $c in
    1) rho=1739 tau=35 eta=0.31 ;;   # 70 %  (mixing_case1.toml at 7dd6c00^)
    *) rho=1790 tau=69 eta=0.47 ;;   # 72.5 % (mixing_case4..7.toml at 7dd6c00^)
  esac
  in="$src/datasets/scenes/mixing_case$c.toml"
  grep -q '^rheology_from' "$in" || { echo "$in: no rheology_from line" >&2; exit 1; }
  sed -e "/^rheology_at *=/d" -e "s|^rheology_from = .*|density = $rho            # kg/m3 (OLD ASSUMED rheology, issue 15)\nyield_stress = $tau         # Pa (OLD ASSUMED)\nplastic_viscosity = $eta  # Pa.s (OLD ASSUMED)|" \
    "$in" > "$out/mixing_case$c.toml"
done
