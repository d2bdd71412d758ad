#!/usr/bin/env bash
# One shard of a seqmassage sequence job, as a Slurm array task or a Kubernetes Indexed Job pod:
# task I runs shard I of N (a contiguous block of the selected frames) into the config's output
# folder on the shared file system; `seqmassage merge` then combines the shards into
# summary.csv, report.json (and sequence.glb). tools/slurm_submit.sh submits both in one command:
#
#   bash tools/slurm_submit.sh configs/take.json 8
#
# or by hand:
#   jobid=$(sbatch --parsable --array=0-7 tools/slurm_shards.sh configs/take.json 8)
#   sbatch --dependency=afterok:$jobid --wrap "seqmassage merge out/take"
#
# A shard that failed (time limit, cancelled, node lost) is run again by its index alone; it
# resumes, keeping the frames it completed:
#   sbatch --array=3 tools/slurm_shards.sh configs/take.json 8
#
# Every task runs the same command line, the one of tools/k8s_indexed_job.yaml too:
#   seqmassage --shard I/N --resume --threads T [options...] CONFIG
# I is $SLURM_ARRAY_TASK_ID, else $JOB_COMPLETION_INDEX (Kubernetes); T is $SLURM_CPUS_PER_TASK,
# else $SEQMASSAGE_THREADS, else the CPUs Slurm gave the task ($SLURM_CPUS_ON_NODE), else 0 (one
# per core). Options after N go to seqmassage. Paths in CONFIG are relative to its folder, so
# every node must see the same paths. The binary is $SEQMASSAGE, else the build of the checkout
# this script belongs to (build/src/cli/seqmassage), else seqmassage on PATH.
#
# The script ends with seqmassage's exit status (it execs it), so Slurm's record of the task is
# the truth: 0 COMPLETED; 143 (SIGTERM: scancel) CANCELLED; at the time limit TIMEOUT; 4 (an I/O
# error, such as another run holding the output folder's lock) and the others FAILED.
#
# Slurm sends SIGTERM at the time limit and on scancel, then SIGKILL after KillWait (30 s by
# default): seqmassage starts no new frame, finishes those in flight and writes its summary and
# report (exit 143). If they take longer than KillWait it is killed, which loses nothing either
# (every file is written atomically, the records say which frames are done). Frames slower than
# that: add --signal=B:TERM@300 (SIGTERM 5 minutes early; the task then ends FAILED, 143, instead
# of TIMEOUT).
#
#SBATCH --job-name=seqmassage
#SBATCH --cpus-per-task=4
#SBATCH --mem=8G
#SBATCH --time=08:00:00
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
if ! [[ $count =~ ^[1-9][0-9]*$ ]]; then
  echo "$0: N must be a positive number of shards, not '$count'" >&2
  exit 2
fi
index=${SLURM_ARRAY_TASK_ID:-${JOB_COMPLETION_INDEX:-}}
if [ -z "$index" ]; then
  echo "$0: not a Slurm array task (sbatch --array=0-$((count - 1)) ...) nor a Kubernetes" \
    "Indexed Job pod (no SLURM_ARRAY_TASK_ID, no JOB_COMPLETION_INDEX)" >&2
  exit 2
fi
if ! [[ $index =~ ^[0-9]+$ ]] || [ "$index" -ge "$count" ]; then
  echo "$0: task $index is not a shard of $count (use --array=0-$((count - 1)))" >&2
  exit 2
fi
threads=${SLURM_CPUS_PER_TASK:-${SEQMASSAGE_THREADS:-${SLURM_CPUS_ON_NODE:-0}}}

# The checkout this script belongs to. sbatch runs a copy of the script from its spool folder;
# the controller knows the submitted path (and its arguments, which end the command).
script=$0
if [ -n "${SLURM_JOB_ID:-}" ] && command -v scontrol >/dev/null; then
  submitted=$(scontrol show job "$SLURM_JOB_ID" 2>/dev/null | sed -n 's/^ *Command=//p' | head -n1)
  submitted=${submitted% "$config $count${*:+ $*}"}
  [ -f "$submitted" ] && script=$submitted
fi
seqmassage=${SEQMASSAGE:-}
if [ -z "$seqmassage" ]; then
  seqmassage="$(cd "$(dirname "$script")/.." 2>/dev/null && pwd)/build/src/cli/seqmassage"
  if [ ! -x "$seqmassage" ]; then
    seqmassage=$(command -v seqmassage || true)
  fi
fi
if [ -z "$seqmassage" ] || [ ! -x "$seqmassage" ]; then
  echo "$0: no seqmassage binary: set SEQMASSAGE, build this checkout, or put it on PATH" >&2
  exit 2
fi

# exec: seqmassage itself receives the scheduler's signals, and its status is the task's.
exec "$seqmassage" --shard "$index/$count" --resume --threads "$threads" "$@" "$config"
