#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Cost of the fluid hook (model/fluid/): the settled bench bed (12,960 spheres, bench/data/bed.csv.gz, the same
# scene as bench/run.sh's "bed") run three ways, alternating, best of N repeats:
#   none     no [[fluid]] table: no FluidField, the step is the engine's own;
#   outside  a [[fluid]] region that no particle enters (a box above the bed): every particle is tested for
#            membership each step and pays nothing else;
#   inside   a region holding every particle: buoyancy + drag kick for all. The fluid is air-like (Newtonian,
#            1.2 kg/m3, 1.8e-5 Pa.s) so the bed's dynamics, hence its contact work, are the same as without it.
#   paste    a Bingham paste (1843 kg/m3, 138 Pa, 0.7 Pa.s, curve 4.19) holding every particle: the settled bed
#            stays at rest in it;
#   cluster  the same paste with collective = "bearing_capacity" (model/fluid/collective.h): the whole bed is
#            one cluster of 12,960 touching spheres, the worst case of the cluster pass (union-find over the
#            pairs, shadowing, footprint), run every collective_interval = 5e-4 s = every 50 steps.
# Prints the step-loop time (the profile's "total wall") and particle-steps/s per variant, and the ratios to
# "none". Usage: bench/fluid_hook.sh [--steps 1000] [--repeats 3] [--threads 1]
# PASTEMIX=/path/to/pastemix to use another build (default build/pastemix); PASTEMIX_BASELINE=/path/to/other
# also runs that build, interleaved with the first (each variant: PASTEMIX then baseline), and prints its table
# and the ratio of the two builds' loop times per variant.
set -euo pipefail
STEPS=1000 REPEATS=3 THREADS=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    --steps) STEPS="$2"; shift 2 ;;
    --repeats) REPEATS="$2"; shift 2 ;;
    --threads) THREADS="$2"; shift 2 ;;
    *) echo "usage: $0 [--steps N] [--repeats N] [--threads N]" >&2; exit 2 ;;
  esac
done
BENCH="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(dirname "$BENCH")"
PASTEMIX="${PASTEMIX:-$ROOT/build/pastemix}"
BASELINE="${PASTEMIX_BASELINE:-}"
BUILDS="new"; [[ -n "$BASELINE" ]] && BUILDS="new base"
PY=/usr/bin/python3
WORK="$(mktemp -d "${TMPDIR:-/tmp}/fluid_hook.XXXXXX")"
trap 'rm -rf "$WORK"' EXIT

"$PY" "$BENCH/tools/csv_to_state.py" "$BENCH/data/bed.csv.gz" "$WORK/bed" >/dev/null
"$PY" "$BENCH/tools/make_scene.py" "$BENCH/scenes/bed.toml" "$WORK/bed.csv" "$WORK/none.toml" --dt 1e-5 \
    --steps "$STEPS" --skin 5e-4 --rolling cdt
AIR='density = 1.2
rheology = "newtonian"
viscosity = 1.8e-5'
{ cat "$WORK/none.toml"; printf '\n[[fluid]]\nname = "above"\nx = [0, 0.165]\ny = [0, 0.2]\nbottom = 0.25\nsurface = 0.29\n%s\n' "$AIR"; } > "$WORK/outside.toml"
{ cat "$WORK/none.toml"; printf '\n[[fluid]]\nname = "all"\nx = [-0.005, 0.17]\ny = [-0.005, 0.205]\nbottom = -0.005\nsurface = 0.29\n%s\n' "$AIR"; } > "$WORK/inside.toml"
PASTE='density = 1843
rheology = "bingham"
yield_stress = 138.0
plastic_viscosity = 0.7
curve = "published_4_19"'
{ cat "$WORK/none.toml"; printf '\n[[fluid]]\nname = "all"\nx = [-0.005, 0.17]\ny = [-0.005, 0.205]\nbottom = -0.005\nsurface = 0.29\n%s\n' "$PASTE"; } > "$WORK/paste.toml"
{ cat "$WORK/paste.toml"; printf 'collective = "bearing_capacity"\n'; } > "$WORK/cluster.toml"

declare -A BEST BCPU
for r in $(seq 1 "$REPEATS"); do
  for v in none outside inside paste cluster; do
    for bld in $BUILDS; do
      bin="$PASTEMIX"; [[ $bld == base ]] && bin="$BASELINE"
      key="$bld.$v" log="$WORK/$bld.$v.$r.log"
      OMP_NUM_THREADS="$THREADS" OMP_WAIT_POLICY=passive "$PY" "$BENCH/tools/cputime.py" "$log.cpu" -- "$bin" run "$WORK/$v.toml" --threads "$THREADS" --quiet \
          --out "$WORK/out_$v" > "$log" 2>&1 || { cat "$log" >&2; exit 1; }
      t=$(awk '/total wall/ {print $3}' "$log")
      c=$(awk '/^cpu_s/ {print $2}' "$log.cpu")
      echo "repeat $r  $bld  $v  loop ${t} s wall, process ${c} s CPU" >&2
      if [[ -z "${BEST[$key]:-}" ]] || awk -v a="$t" -v b="${BEST[$key]}" 'BEGIN {exit !(a < b)}'; then BEST[$key]=$t; fi
      if [[ -z "${BCPU[$key]:-}" ]] || awk -v a="$c" -v b="${BCPU[$key]}" 'BEGIN {exit !(a < b)}'; then BCPU[$key]=$c; fi
    done
  done
done
N=$(grep -c '^\[\[particle\]\]' "$WORK/none.toml")
for bld in $BUILDS; do
  bin="$PASTEMIX"; [[ $bld == base ]] && bin="$BASELINE"
  printf 'fluid hook cost: bench bed, %s spheres, %s steps, %s thread(s), best of %s (alternating runs), %s\n' "$N" "$STEPS" "$THREADS" "$REPEATS" "$bin"
  printf '%-8s %10s %17s %16s %9s %13s %9s\n' variant "loop s" "ns/particle-step" "particle-steps/s" "vs none" \
      "process CPU s" "vs none"
  for v in none outside inside paste cluster; do
    awk -v v="$v" -v t="${BEST[$bld.$v]}" -v t0="${BEST[$bld.none]}" -v c="${BCPU[$bld.$v]}" -v c0="${BCPU[$bld.none]}" -v n="$N" \
        -v s="$STEPS" 'BEGIN {printf "%-8s %10.3f %17.1f %16.4g %9.4f %13.3f %9.4f\n", v, t, 1e9 * t / (n * s), n * s / t,
                              t / t0, c, c / c0}'
  done
done
if [[ -n "$BASELINE" ]]; then
  printf 'loop time, this build / baseline:'
  for v in none outside inside paste cluster; do
    awk -v v="$v" -v a="${BEST[new.$v]}" -v b="${BEST[base.$v]}" 'BEGIN {printf "  %s %.3f", v, a / b}'
  done
  echo
fi
echo "(loop s: the step loop's wall time from the run's profile; process CPU: whole process incl. scene parse and output)"
