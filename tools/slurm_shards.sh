#!/usr/bin/env bash
# A seqmassage sequence job as a Slurm job array: array task I runs shard I of N (a contiguous
# block of the selected frames) into the config's output folder on the shared file system; a
# dependent job merges the shards into summary.csv, report.json (and sequence.glb).
#
#   N=8
#   jobid=$(sbatch --parsable --array=0-$((N - 1)) tools/slurm_shards.sh configs/take.json $N)
#   sbatch --dependency=afterok:$jobid --wrap "seqmassage merge out/take"
#
# A shard that failed (time limit, node lost, preempted) is run again by its index alone; it
# resumes, keeping the frames it completed:
#   sbatch --array=3 tools/slurm_shards.sh configs/take.json 8
#
# Every task runs the same command line, the one of tools/k8s_indexed_job.yaml:
#   seqmassage --shard I/N --resume [--threads T] CONFIG
# Paths in CONFIG are relative to its folder, so every node must see the same paths. The binary
# is $SEQMASSAGE, or seqmassage on PATH, or build/src/cli/seqmassage of this checkout.
#
# Slurm sends SIGTERM at the time limit (and on scancel), then SIGKILL after KillWait (30 s by
# default): seqmassage stops after the frames in flight (exit 143); if those take longer than
# KillWait it is killed, which loses nothing either (every file is written atomically, the
# records say which frames are done). --signal=B:TERM@180 below warns it 3 minutes early.
#
#SBATCH --job-name=seqmassage
#SBATCH --cpus-per-task=4
#SBATCH --mem=8G
#SBATCH --time=08:00:00
#SBATCH --signal=B:TERM@180
#SBATCH --requeue
#SBATCH --output=seqmassage-%A_%a.log
set -euo pipefail

if [ $# -lt 2 ]; then
  echo "usage: sbatch --array=0-<N-1> $0 CONFIG.json N [seqmassage options...]" >&2
  exit 2
fi
config=$1
count=$2
shift 2
index=${SLURM_ARRAY_TASK_ID:?"not in a Slurm job array (sbatch --array=0-$((count - 1)) ...)"}
if ! [[ $count =~ ^[0-9]+$ ]] || [ "$index" -ge "$count" ]; then
  echo "$0: array task $index is not a shard of $count (use --array=0-$((count - 1)))" >&2
  exit 2
fi

seqmassage=${SEQMASSAGE:-}
if [ -z "$seqmassage" ]; then
  if command -v seqmassage >/dev/null; then
    seqmassage=seqmassage
  else
    # sbatch runs a copy of this script: find the checkout from where it was submitted.
    seqmassage="${SLURM_SUBMIT_DIR:-$(dirname "$0")/..}/build/src/cli/seqmassage"
  fi
fi

# exec: seqmassage itself receives Slurm's signals.
exec "$seqmassage" --shard "$index/$count" --resume --threads "${SLURM_CPUS_PER_TASK:-0}" \
  "$@" "$config"
