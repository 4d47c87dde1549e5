#!/usr/bin/env bash
# One task of a pastemix study per Slurm array index (app/study/README.md, "Many machines").
#
#   N=15   # the study's task count: points x seeds (a sweep: values x seeds)
#   A=$(sbatch --parsable --array=0-$((N-1)) app/study/slurm_array.sh calibrate rolling-resistance SCENE ... --out OUT)
#   sbatch --dependency=afterany:$A --wrap "pastemix calibrate rolling-resistance SCENE ... --out OUT --ledger L.csv"
#
# Every array job runs `pastemix ARGS --task-index $SLURM_ARRAY_TASK_ID`: that one task (or nothing if it is
# finished, or if the index is past the list), its record written to OUT/runs/<key>.toml on the shared file
# system. The dependent job, the same command without --task-index, reads every record back, appends them to
# the ledger and writes the study's outputs (array jobs never append to the ledger at once). A job that was
# killed (time limit, preemption) left its checkpoint in OUT/runs: resubmit the same index to continue it.
#SBATCH --job-name=pastemix-study
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --time=04:00:00
#SBATCH --output=pastemix-study-%A_%a.out
set -euo pipefail
if [ -z "${SLURM_ARRAY_TASK_ID:-}" ]; then
  echo "slurm_array.sh: SLURM_ARRAY_TASK_ID is not set: submit it as a job array, sbatch --array=0-N $0 ARGS" >&2
  exit 2
fi
if [ $# -eq 0 ]; then
  echo "slurm_array.sh: give the study command, e.g. calibrate rolling-resistance SCENE --target 33.47 ..." >&2
  exit 2
fi
# One thread per task: the tasks are the parallelism (and the engine's bits do not depend on it).
export OMP_NUM_THREADS=1
exec "${PASTEMIX:-pastemix}" "$@" --task-index "$SLURM_ARRAY_TASK_ID"
