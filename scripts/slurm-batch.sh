#!/usr/bin/env bash
# Meshes one shard of a list of inputs per task of a Slurm job array:
#
#   CLMESH=/path/to/clmesh sbatch --array=1-8 scripts/slurm-batch.sh LIST [SWITCHES...]
#
# Task K of the N tasks (K counted from 1 in array order, whatever the ids:
# --array=0-7 and --array=1-15:2 work too) runs
#
#   $CLMESH SWITCHES... --batch LIST --shard K/N
#
# which meshes the inputs at positions K, K+N, K+2N... of LIST. Together the
# tasks write exactly the files of `$CLMESH SWITCHES... --batch LIST`, each
# as `$CLMESH SWITCHES... FILE` would (docs/batch.md). Exit status: clmesh's
# (1 when an input of the shard failed); 2 outside a job array.
#SBATCH --job-name=clmesh-batch
#SBATCH --ntasks=1
set -euo pipefail

if [[ $# -lt 1 ]]; then
  echo "usage: sbatch --array=1-N $0 LIST [CLMESH SWITCHES...]" >&2
  exit 2
fi
if [[ -z "${SLURM_ARRAY_TASK_ID:-}" || -z "${SLURM_ARRAY_TASK_COUNT:-}" ]]; then
  echo "$0: SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT are not set: submit it as a job array (sbatch --array=1-N)" >&2
  exit 2
fi
list="$1"
shift
first="${SLURM_ARRAY_TASK_MIN:-1}"
step="${SLURM_ARRAY_TASK_STEP:-1}"
shard=$(((SLURM_ARRAY_TASK_ID - first) / step + 1))
exec "${CLMESH:-clmesh}" "$@" --batch "$list" --shard "$shard/$SLURM_ARRAY_TASK_COUNT"
