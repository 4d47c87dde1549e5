#!/usr/bin/env bash
# The issue-15 driver of session 11 (run from the frozen 4921aa5 tree, paths of that machine): the order the runs were queued in.
# issue-15 runs after the calibration: band 4,5 -> old 4,5 -> band 1 -> old 1 -> band 6,7 -> sensitivity
set -u
cd /work/cal/src
px=./build/pastemix
L=/work/main/docs/studies
while pgrep -f "calibrate rheology --case 2 --seeds 3" > /dev/null; do sleep 30; done
rec=/work/cal/case2/rheology_calibration.toml
[[ -f $rec ]] || { echo "no record"; exit 1; }
$px lab reduce datasets/thesis --rheology-calibration $rec --out /work/cal/labrec > /work/cal/labrec.log 2>&1 || { echo "reduce failed"; exit 1; }
band() { $px predict rheology --calibration $rec --cases $1 --seeds 3 --jobs 2 \
  --overrides $L/rheology_band.overrides.toml --params /work/cal/labrec/parameters.toml \
  --lab-h5 /work/cal/labrec/lab.h5 --out /work/cal/band --ledger $L/rheology_band.csv; }
old() { bash $L/rheology_old/run.sh $PWD/$px /work/cal/src /work/cal/labrec /work/cal/old 2 "$@"; }
echo "== band 4,5 $(date)"; band 4,5
echo "== old 4 5 $(date)"; old 4 5
echo "== band 1 $(date)"; band 1
echo "== old 1 $(date)"; old 1
echo "== band 6,7 $(date)"; band 6,7
b=$(grep -m1 '^shape *=' $rec | sed 's/.*= *//; s/ .*//')
for f in 1 0.5 1.5; do
  echo "== sensitivity eta x $f (b = $b) $(date)"
  $px calibrate rheology --case 2 --seeds 3 --jobs 2 --values $b --refine 0 --eta-factor $f \
    --overrides $L/rheology_band.overrides.toml --params /work/cal/lab/parameters.toml --lab-h5 /work/cal/lab/lab.h5 \
    --out /work/cal/sens_$f --no-store --ledger $L/rheology_sensitivity.csv
done
echo "== all done $(date)"
