#!/usr/bin/env bash
# Submits a seqmassage sequence job to Slurm as N shards: a job array of tools/slurm_shards.sh
# (task I runs shard I of N) and a merge job that runs when every task succeeded
# (--dependency=afterok), then prints the two job ids (N = 1: the array alone, whose one task
# writes summary.csv and report.json itself):
#
#   bash tools/slurm_submit.sh [sbatch options...] CONFIG.json N [seqmassage options...]
#   array 1234
#   merge 1235
#
# sbatch options (before CONFIG, in the --name=value form) apply to the array's tasks, over the
# defaults in tools/slurm_shards.sh (--cpus-per-task=4 --mem=8G --time=08:00:00), for example
# --cpus-per-task=2 --time=1:00:00 --partition=batch, and to the merge job too but for its one
# CPU, name and log. The tasks' logs are seqmassage-<array>_<task>.log (unless --output is
# given) and the merge's seqmassage-merge-<job>.log, in the folder this is run from.
#
# The config is checked first (seqmassage --dry-run of shard 0), so a bad config is refused
# before anything is queued. When a task fails, Slurm cancels the merge job (its dependency can no
# longer be met): resubmit the task by its index (it resumes) and merge after it,
#   id=$(sbatch --parsable --array=3 tools/slurm_shards.sh CONFIG.json N)
#   sbatch --dependency=afterok:$id --wrap "seqmassage merge OUTPUT_DIR"
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

sbatch_options=()
while [ $# -gt 0 ] && [[ $1 == -* ]]; do
  sbatch_options+=("$1")
  shift
done
if [ $# -lt 2 ]; then
  echo "usage: bash $0 [sbatch options...] CONFIG.json N [seqmassage options...]" >&2
  exit 2
fi
config=$1
count=$2
shift 2
if ! [[ $count =~ ^[1-9][0-9]*$ ]]; then
  echo "$0: N must be a positive number of shards, not '$count'" >&2
  exit 2
fi
if [ ! -f "$config" ]; then
  echo "$0: no config file '$config'" >&2
  exit 2
fi
config="$(cd "$(dirname "$config")" && pwd)/$(basename "$config")"

seqmassage=${SEQMASSAGE:-$here/../build/src/cli/seqmassage}
[ -x "$seqmassage" ] || seqmassage=$(command -v seqmassage || true)
if [ -z "$seqmassage" ]; then
  echo "$0: no seqmassage binary: set SEQMASSAGE, build this checkout, or put it on PATH" >&2
  exit 2
fi
seqmassage="$(cd "$(dirname "$seqmassage")" && pwd)/$(basename "$seqmassage")"

# The whole config and shard 0's frames checked here; the output folder as the job sees it.
plan=$("$seqmassage" --dry-run --shard "0/$count" "$@" "$config") || exit $?
output_dir=$(sed -n 's/^output: //p' <<<"$plan" | head -n1)
if [ -z "$output_dir" ]; then
  echo "$0: seqmassage --dry-run named no output folder" >&2
  exit 1
fi

export SEQMASSAGE="$seqmassage"
array=$(sbatch --parsable --array="0-$((count - 1))" "${sbatch_options[@]}" \
  "$here/slurm_shards.sh" "$config" "$count" "$@")
array=${array%%;*}
echo "array $array"
if [ "$count" = 1 ]; then
  # One shard is the whole job: the task writes summary.csv and report.json itself.
  echo "$0: N = 1: no merge job (the task writes summary.csv and report.json)" >&2
  exit 0
fi
merge=$(sbatch --parsable "${sbatch_options[@]}" --job-name=seqmassage-merge --cpus-per-task=1 \
  --dependency="afterok:$array" --kill-on-invalid-dep=yes --output=seqmassage-merge-%j.log \
  --wrap "exec $(printf '%q ' "$seqmassage" merge "$output_dir")")
merge=${merge%%;*}
echo "merge $merge"
