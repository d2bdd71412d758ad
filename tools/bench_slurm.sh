#!/usr/bin/env bash
# Scaling of a sharded sequence job on the local Slurm cluster (tools/slurm_local.sh), issue 17:
#  1. one job of F generated frames (a bending tube of about V vertices, written as OBJ frames
#     first, so that no shard regenerates the input) submitted by tools/slurm_submit.sh as N = 1,
#     2, 4 tasks of --cpus-per-task 1 and 2: the wall time from submission to the merged result
#     (polling squeue every 0.1 s), the configurations interleaved, R rounds, medians; beside it
#     the same job run directly (seqmassage --threads 1 and 2, no scheduler) and an empty job's
#     round trip through Slurm (sbatch --wrap true, polled the same way);
#  2. the per-task start-up (template, weights, system, first frame) at 10k and 150k vertices,
#     by build/tools/bench_shard_startup, and the frames per task that keep it under 1 %.
# Every merged summary.csv is compared with the direct run's. Prints tables; asserts nothing.
#
#   bash tools/bench_slurm.sh [--repeat R] [--frames F] [--vertices V] [--no-startup]
# Needs the Release build (cmake --build build --target seqmassage bench_shard_startup). Uses the
# cluster of tools/slurm_local.sh (started if it is not running, and then stopped at the end).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seqmassage="$root/build/src/cli/seqmassage"
startup_bench="$root/build/tools/bench_shard_startup"
repeat=3 frames=64 vertices=10000 startup=1
while [ $# -gt 0 ]; do
  case "$1" in
    --repeat) repeat=$2 && shift 2 ;;
    --frames) frames=$2 && shift 2 ;;
    --vertices) vertices=$2 && shift 2 ;;
    --no-startup) startup=0 && shift ;;
    *)
      echo "usage: bash $0 [--repeat R] [--frames F] [--vertices V] [--no-startup]" >&2
      exit 2
      ;;
  esac
done
for f in "$seqmassage" "$startup_bench"; do
  [ -x "$f" ] || {
    echo "bench_slurm: no $f: cmake --build build --target seqmassage bench_shard_startup" >&2
    exit 2
  }
done

stop_at_end=0
if ! bash "$root/tools/slurm_local.sh" status >/dev/null 2>&1; then
  bash "$root/tools/slurm_local.sh" start
  stop_at_end=1
fi
[ "$stop_at_end" = 0 ] || trap 'bash "$root/tools/slurm_local.sh" stop' EXIT
eval "$(bash "$root/tools/slurm_local.sh" env)"
cpus=$(sinfo -h -N -o %c | head -n1)

work="$root/build/bench-slurm"
rm -rf "$work"
mkdir -p "$work/logs"
cd "$work"
now() { date +%s.%N; }
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2)}'; }
minmax() { sort -g | awk 'NR == 1 {lo = $1} {hi = $1} END {printf "%.1f-%.1f", lo, hi}'; }

# The input: F frames of a tube with about V vertices (segments around ~ sqrt(0.6 V)).
segments=$(awk -v v="$vertices" 'BEGIN {s = int(sqrt(0.6 * v)); print (s < 8 ? 8 : s)}')
rings=$((vertices / segments - 1))
cat >generate.json <<EOF
{ "job": "sequence", "input": { "synthetic": { "frames": $frames, "segments": $segments,
  "rings": $rings } }, "output": { "dir": "generated", "timings": false } }
EOF
"$seqmassage" -q --frames 0 generate.json
cat >job.json <<'EOF'
{ "job": "sequence", "input": { "frames": "generated/input" },
  "output": { "dir": "out", "timings": false } }
EOF
echo "bench_slurm: $frames frames of $((segments * (rings + 1))) vertices, a $cpus-CPU node," \
  "$repeat rounds; load average $(cut -d' ' -f1-3 /proc/loadavg)"

jobs_done() { [ -z "$(squeue -h -j "$1" -o %i)" ]; }
# One submission: wall seconds from slurm_submit.sh to the merge's end.
submit_and_wait() { # submit_and_wait N CPUS
  rm -rf out
  local t0 ids array merge
  t0=$(now)
  ids=$(bash "$root/tools/slurm_submit.sh" --cpus-per-task="$2" --mem=1G \
    --output="$work/logs/%A_%a.log" job.json "$1")
  array=$(awk '$1 == "array" {print $2}' <<<"$ids")
  merge=$(awk '$1 == "merge" {print $2}' <<<"$ids")
  until jobs_done "$array${merge:+,$merge}"; do sleep 0.1; done
  awk -v a="$t0" -v b="$(now)" 'BEGIN {printf "%.2f\n", b - a}'
  local state
  state=$(scontrol show job -o "${merge:-$array}" | tr ' ' '\n' | sed -n 's/^JobState=//p')
  [ "$state" = COMPLETED ] || echo "bench_slurm: job ${merge:-$array} is $state" >&2
  cmp -s out/summary.csv direct-summary.csv || echo "bench_slurm: N=$1: summary.csv differs" >&2
}
direct() { # direct THREADS: the job without the scheduler
  rm -rf out
  local t0
  t0=$(now)
  "$seqmassage" -q --threads "$1" job.json
  awk -v a="$t0" -v b="$(now)" 'BEGIN {printf "%.2f\n", b - a}'
  cp out/summary.csv direct-summary.csv
}
empty_job() {
  local t0 id
  t0=$(now)
  id=$(sbatch --parsable --output=/dev/null --wrap true)
  until jobs_done "$id"; do sleep 0.1; done
  awk -v a="$t0" -v b="$(now)" 'BEGIN {printf "%.2f\n", b - a}'
}

configs=("1 1" "1 2" "2 1" "2 2" "4 1" "4 2")
for ((r = 1; r <= repeat; r++)); do
  direct 1 >>"direct-1.txt"
  direct 2 >>"direct-2.txt"
  empty_job >>"empty.txt"
  for c in "${configs[@]}"; do
    read -r n k <<<"$c"
    submit_and_wait "$n" "$k" >>"slurm-$n-$k.txt"
  done
  echo "bench_slurm: round $r of $repeat done"
done

echo
echo "wall time to the merged result, seconds (median of $repeat, range), $frames frames"
printf '%-44s %8s %12s %9s\n' "run" "median" "range" "speed-up"
base=$(median <"slurm-1-1.txt")
row() { printf '%-44s %8.1f %12s %8.2fx\n' "$1" "$(median <"$2")" "$(minmax <"$2")" \
  "$(awk -v b="$base" -v m="$(median <"$2")" 'BEGIN {print b / m}')"; }
row "direct, --threads 1 (no Slurm)" direct-1.txt
row "direct, --threads 2 (no Slurm)" direct-2.txt
for c in "${configs[@]}"; do
  read -r n k <<<"$c"
  at_once=$((cpus / k < n ? cpus / k : n))
  row "Slurm N=$n, --cpus-per-task=$k ($at_once at once)" "slurm-$n-$k.txt"
done
printf '%-44s %8.1f %12s\n' "Slurm, an empty job (round trip)" "$(median <empty.txt)" "$(minmax <empty.txt)"

if [ "$startup" = 1 ]; then
  echo
  "$startup_bench" --sizes 10000,150000 --repeat "$repeat"
fi
