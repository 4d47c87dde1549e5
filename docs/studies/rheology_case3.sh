#!/usr/bin/env bash
# Session 13 (run from /work/cal/src at 4921aa5). Issue 15 trend table: case 3 (75 %, the measured paste: the anchor, identical under the old and new rheology),
# 3 seeds (the scene's 3 and the next two), the band's overrides, frozen engine 4921aa5, one thread, one at a time.
set -u
cd /work/cal/src
px=./build/pastemix
L=/work/main/docs/studies
[[ -f /work/cal/lab/lab.h5 ]] || $px lab reduce datasets/thesis --out /work/cal/lab > /work/cal/lab.log 2>&1
for s in 3 4 5; do
  d=/work/cal/case3/seed$s
  [[ -f $d/done ]] && continue
  mkdir -p $d
  echo "== case 3 seed $s $(date)"
  $px run datasets/scenes/mixing_case3.toml --overrides $L/rheology_band.overrides.toml --set seed=$s --threads 1 --quiet --out $d > $d/run.log 2>&1 && touch $d/done
done
$px score /work/cal/case3/seed*/mixing_case3.h5 --lab 3 --lab-h5 /work/cal/lab/lab.h5 --out /work/cal/case3/score > /work/cal/case3/score.txt 2>&1
echo "== all done $(date)"
