#!/usr/bin/env bash
# The cluster path through a real scheduler: a private single-node Slurm cluster
# (tools/slurm_local.sh) runs tools/slurm_shards.sh and tools/slurm_submit.sh on a generated
# 60-frame sequence, and the failure paths a scheduler exists for:
#   array     4 tasks + a merge job (--dependency=afterok): summary.csv, report.json and every
#             frame byte-identical to one unsharded run ("timings": false)
#   cancel    one array task scancel'ed while it writes, resubmitted by its index: it keeps the
#             frames it completed (their record files are not rewritten) and the merge matches
#   timeout   a task past its --time: Slurm ends it with SIGTERM (seqmassage finishes the frame in
#             flight, exit 143, JobState TIMEOUT), no partial file, its frames resumable
#   duplicate two copies of one task at once: the second is refused by the output folder's lock
#             (exit 4, naming the holder) and Slurm records it FAILED
# Every wait polls (squeue, files) with a timeout; no timing is asserted. At the end the
# scheduler's own record of those jobs (scontrol show job) is written to
# build/slurm-test/scheduler-record.txt and printed.
#   bash tests/tools/test_slurm.sh     (tools/test.sh runs it after the Release build)
# Exit status: 0 passed; 1 failed; 3 skipped (Slurm cannot be installed here).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
seqmassage="$root/build/src/cli/seqmassage"
work="$root/build/slurm-test"
started=$SECONDS

log() { echo "test_slurm: $*"; }
fail() {
  echo "test_slurm: FAILED: $*" >&2
  exit 1
}
[ -x "$seqmassage" ] || fail "no $seqmassage: build first (cmake --build build)"

# A cluster of the test's own, so that a cluster the user started is left alone.
SEQMASSAGE_SLURM_DIR="/tmp/seqmassage-slurm-test-$(id -u)-$(printf '%s' "$root" | cksum | cut -d' ' -f1)"
export SEQMASSAGE_SLURM_DIR
status=0
bash "$root/tools/slurm_local.sh" start || status=$?
if [ "$status" = 3 ]; then
  log "SKIPPED: Slurm cannot be installed on this machine (see above)"
  exit 3
fi
[ "$status" = 0 ] || fail "the local Slurm cluster did not start (see above)"
trap 'bash "$root/tools/slurm_local.sh" stop' EXIT
eval "$(bash "$root/tools/slurm_local.sh" env)"
unset SEQMASSAGE # the scripts must find the checkout's build themselves

rm -rf "$work"
mkdir -p "$work/logs"
cd "$work"
tasks=(--cpus-per-task=1 --mem=1G) # fits any CI machine; --threads 1 in every task

# --- Helpers -----------------------------------------------------------------------------------

poll() { # poll SECONDS WHAT COMMAND...: every 0.1 s until COMMAND succeeds
  local limit=$1 what=$2
  local deadline=$((SECONDS + limit))
  shift 2
  until "$@"; do
    [ "$SECONDS" -lt "$deadline" ] || fail "timed out after $limit s waiting for $what"
    sleep 0.1
  done
}
# No job of the comma-separated list pending or running any more.
jobs_done() {
  local out
  out=$(squeue -h -j "$1" -o %i) || return 1
  [ -z "$out" ]
}
wait_jobs() { poll "$1" "jobs $2 to end (squeue)" jobs_done "$2"; }
field() { # field JOB KEY: KEY's value in `scontrol show job -o JOB` (first line)
  scontrol show job -o "$1" | head -n1 | tr ' ' '\n' | sed -n "s/^$2=//p" | head -n1
}
expect_state() { # expect_state JOB STATE [EXITCODE]
  local state code
  state=$(field "$1" JobState)
  code=$(field "$1" ExitCode)
  [ "$state" = "$2" ] || fail "job $1 is $state (exit $code), expected $2"
  [ -z "${3:-}" ] || [ "$code" = "$3" ] || fail "job $1 ($state) has exit code $code, expected $3"
}
no_temporaries() {
  local left
  left=$(find "$1" -name '*.seqmassage-tmp' | head -n3)
  [ -z "$left" ] || fail "partial files left in $1: $left"
}
same_as_reference() { # every file of one run, byte for byte (the shards' and locks' files aside)
  diff -r -x '*.shard-*' -x '*lock*' "$work/reference" "$1" >"$work/logs/diff.txt" ||
    fail "$1 differs from the unsharded run: $(head -n5 "$work/logs/diff.txt")"
  cmp -s "$work/reference/summary.csv" "$1/summary.csv" || fail "summary.csv differs"
}
# "inode mtime sha256 name" of each record, to tell a record kept from one written again.
snapshot() {
  local f
  for f in "$@"; do
    printf '%s %s\n' "$(stat -c '%i %Y' "$f")" "$(sha256sum "$f")"
  done
}
block_records() { # block_records DIR FIRST LAST: the record files present of frames FIRST..LAST
  local i r
  for ((i = $2; i <= $3; i++)); do
    r="$1/records/$(printf 'frame_%04d.json' "$i")"
    [ -f "$r" ] && echo "$r"
  done
  return 0
}
has_records() { [ "$(block_records "$1" "$2" "$3" | wc -l)" -ge "$4" ]; }
recorded=() # job ids for the scheduler record at the end, with what they were
record() { recorded+=("$1|$2"); }

# --- The jobs ----------------------------------------------------------------------------------

# One 60-frame generated sequence; more outer iterations than the default (200, no early stop)
# make each frame long enough that a task is reliably seen mid-run.
mkdir -p job
cat >job/job.json <<'EOF'
{ "job": "sequence", "input": { "synthetic": { "frames": 60 } },
  "massage": { "iterations": 200, "tolerance": 0 },
  "output": { "dir": "out", "timings": false } }
EOF
# The slow job: 240 generated frames (written once, by a run of the template frame alone), 4000
# outer iterations each (about a second a frame) and one frame in flight, so that a task
# outlives a one-minute limit on any machine and still stops well within KillWait (30 s).
mkdir -p slow
cat >slow/job.json <<'EOF'
{ "job": "sequence", "input": { "synthetic": { "frames": 240 } },
  "output": { "dir": "out", "timings": false } }
EOF
for name in timeout duplicate; do
  mkdir -p "$name"
  cat >"$name/job.json" <<'EOF'
{ "job": "sequence", "input": { "frames": "../slow/out/input" }, "frames_in_flight": 1,
  "massage": { "iterations": 4000, "tolerance": 0 },
  "output": { "dir": "out", "timings": false } }
EOF
done

log "the unsharded run (--threads 1, as every task)"
"$seqmassage" -q --threads 1 job/job.json
"$seqmassage" -q --frames 0 slow/job.json
# Runs write job/out: the reference moves aside so that every run has the same paths, which
# report.json records.
mv job/out reference

# --- Duplicate: two copies of one task at once (needs both CPUs, so first) ----------------------
log "duplicate: task 1 of 4 twice at once"
first=$(sbatch --parsable "${tasks[@]}" --array=1 --output="$work/logs/duplicate-first-%j.log" \
  "$root/tools/slurm_shards.sh" duplicate/job.json 4)
record "$first" "duplicate, the first copy (cancelled when the test is done with it)"
lock_or_record() {
  [ -n "$(find duplicate/out -maxdepth 2 -iname '*lock*' 2>/dev/null | head -n1)" ] ||
    has_records duplicate/out 60 119 1
}
poll 120 "the first copy to hold the output folder" lock_or_record
lock_file=$(find duplicate/out -maxdepth 2 -iname '*lock*' 2>/dev/null | head -n1)
holder=$(scontrol listpids "$first" 2>/dev/null | awk 'NR > 1 && $1 ~ /^[0-9]+$/ {print $1; exit}')
second=$(sbatch --parsable "${tasks[@]}" --array=1 --output="$work/logs/duplicate-second-%j.log" \
  "$root/tools/slurm_shards.sh" duplicate/job.json 4)
record "$second" "duplicate, the second copy (the lock must refuse it)"
second_log="$work/logs/duplicate-second-$second.log"
# A progress line of a frame it processed (not one kept from the first copy's records).
second_wrote() { grep '^frame ' "$second_log" 2>/dev/null | grep -vq 'kept from an earlier run'; }
second_ended_or_wrote() { jobs_done "$second" || second_wrote; }
poll 120 "the second copy to be refused or to write" second_ended_or_wrote
lock_missing=""
if jobs_done "$second"; then
  expect_state "$second" FAILED 4:0
  grep -q "$(hostname)" "$second_log" || fail "the refusal does not name the host: $(cat "$second_log")"
  [ -z "$holder" ] || grep -q "$holder" "$second_log" ||
    fail "the refusal does not name the holder's pid $holder: $(cat "$second_log")"
  expect_state "${first}" RUNNING
  log "duplicate: refused, Slurm: FAILED 4:0: $(grep -i lock "$second_log" | head -n1)"
else
  lock_missing="the second copy ran alongside the first and wrote a frame (no lock file in the output folder${lock_file:+ but $lock_file})"
  [ -z "$lock_file" ] || fail "duplicate: $lock_missing"
  scancel "$second"
fi
scancel "$first"
wait_jobs 90 "$first,$second"
expect_state "$first" CANCELLED
no_temporaries duplicate/out

# --- Timeout: a task past its --time (one minute; Slurm checks limits every 30 s) ---------------
log "timeout: the slow job as one task (240 frames), --time=1"
timeout=$(sbatch --parsable "${tasks[@]}" --array=0 --time=1 \
  --output="$work/logs/timeout-%j.log" "$root/tools/slurm_shards.sh" timeout/job.json 1)
record "$timeout" "the time-limited task"

# --- Array: 4 tasks and the merge, by tools/slurm_submit.sh --------------------------------------
log "array: bash tools/slurm_submit.sh ${tasks[*]} job/job.json 4"
ids=$(bash "$root/tools/slurm_submit.sh" "${tasks[@]}" --output="$work/logs/array-%A_%a.log" \
  job/job.json 4)
array=$(awk '$1 == "array" {print $2}' <<<"$ids")
merge=$(awk '$1 == "merge" {print $2}' <<<"$ids")
[ -n "$array" ] && [ -n "$merge" ] || fail "slurm_submit.sh printed no job ids: $ids"
record "$array" "the array (4 tasks)"
record "$merge" "its merge job (afterok)"
[[ $(field "$merge" Dependency) == afterok:${array}_* ]] ||
  fail "the merge job's dependency is $(field "$merge" Dependency)"
wait_jobs 300 "$array,$merge"
for t in 0 1 2 3; do expect_state "${array}_$t" COMPLETED 0:0; done
expect_state "$merge" COMPLETED 0:0
same_as_reference job/out
log "array: 4 tasks and the merge COMPLETED; all $(find job/out -type f ! -name '*.shard-*' | wc -l) files identical to the unsharded run"
rm -rf job/out

# --- Cancel: one task scancel'ed while it writes, then resubmitted -------------------------------
log "cancel: sbatch --array=0-3 tools/slurm_shards.sh job/job.json 4; scancel of task 1 mid-run"
cancel=$(sbatch --parsable "${tasks[@]}" --array=0-3 --output="$work/logs/cancel-%A_%a.log" \
  "$root/tools/slurm_shards.sh" job/job.json 4)
record "${cancel}_1" "the cancelled task"
poll 300 "task 1 to complete a frame" has_records job/out 15 29 1
scancel "${cancel}_1"
wait_jobs 300 "$cancel"
expect_state "${cancel}_1" CANCELLED
for t in 0 2 3; do expect_state "${cancel}_$t" COMPLETED 0:0; done
cancel_log="$work/logs/cancel-${cancel}_1.log"
grep -q 'terminated (SIGTERM)' "$cancel_log" ||
  fail "task 1 did not stop on SIGTERM: $(tail -n3 "$cancel_log")"
no_temporaries job/out
mapfile -t kept < <(block_records job/out 15 29)
[ "${#kept[@]}" -ge 1 ] && [ "${#kept[@]}" -lt 15 ] ||
  fail "task 1 has ${#kept[@]} of its 15 frames after scancel"
snapshot "${kept[@]}" >"$work/logs/cancel-records-before.txt"
grep -q '"complete": false' job/out/report.shard-1-of-4.json ||
  fail "report.shard-1-of-4.json does not say the shard is incomplete"
log "cancel: task 1 CANCELLED after ${#kept[@]} of 15 frames; resubmitting it with --array=1"
again=$(sbatch --parsable "${tasks[@]}" --array=1 --output="$work/logs/resume-%A_%a.log" \
  "$root/tools/slurm_shards.sh" job/job.json 4)
record "$again" "the cancelled task resubmitted (resumes)"
merge2=$(sbatch --parsable --mem=1G --dependency="afterok:$again" \
  --output="$work/logs/resume-merge-%j.log" --wrap "exec $(printf '%q ' "$seqmassage" merge "$work/job/out")")
wait_jobs 300 "$again,$merge2"
expect_state "$again" COMPLETED 0:0
expect_state "$merge2" COMPLETED 0:0
resumed="resume: ${#kept[@]} frames kept from earlier runs, $((15 - ${#kept[@]})) processed"
grep -qF "$resumed" "$work/logs/resume-${again}_1.log" ||
  fail "expected '$resumed' in the resubmitted task's log: $(grep resume "$work/logs/resume-${again}_1.log")"
snapshot "${kept[@]}" | cmp -s - "$work/logs/cancel-records-before.txt" ||
  fail "records of frames completed before scancel were written again"
same_as_reference job/out
log "cancel: $resumed (their record files untouched: same inode, time, SHA-256); merge identical"
rm -rf job/out

# --- Timeout, the end -------------------------------------------------------------------------
wait_jobs 300 "$timeout"
[ "$(field "$timeout" JobState)" != COMPLETED ] ||
  fail "the slow job finished within its one-minute limit here: give it more iterations"
expect_state "$timeout" TIMEOUT 143:0
timeout_log="$work/logs/timeout-$timeout.log"
grep -q 'DUE TO TIME LIMIT' "$timeout_log" || fail "Slurm's time-limit message missing: $(cat "$timeout_log")"
grep -q 'terminated (SIGTERM)' "$timeout_log" ||
  fail "the task did not stop on SIGTERM: $(tail -n3 "$timeout_log")"
no_temporaries timeout/out
done_frames=$(block_records timeout/out 0 239 | wc -l)
[ "$done_frames" -ge 1 ] && [ "$done_frames" -lt 240 ] ||
  fail "the timed-out task has $done_frames of 240 frames"
grep -q '"interrupted": true' timeout/out/report.json ||
  fail "report.json does not say the run was interrupted"
[ "$(($(wc -l <timeout/out/summary.csv) - 1))" = "$done_frames" ] ||
  fail "summary.csv does not list the $done_frames frames done"
# Resumable: the frames it completed, run again through Slurm, are all kept (none recomputed).
check=$(sbatch --parsable "${tasks[@]}" --array=0 --output="$work/logs/timeout-resume-%j.log" \
  "$root/tools/slurm_shards.sh" timeout/job.json 1 --frames "0:$done_frames")
wait_jobs 120 "$check"
expect_state "$check" COMPLETED 0:0
grep -qF "resume: $done_frames frames kept from earlier runs, 0 processed" \
  "$work/logs/timeout-resume-$check.log" || fail "the timed-out task's frames are not resumable: \
$(grep resume "$work/logs/timeout-resume-$check.log")"
log "timeout: TIMEOUT after $done_frames frames, SIGTERM first (exit 143), no partial file; all $done_frames resumable"

# --- The scheduler's record --------------------------------------------------------------------
{
  echo "# scontrol show job, $(date -u +%FT%TZ), $(sinfo -h -N -o '%N: %c CPUs, %m MB')"
  for entry in "${recorded[@]}"; do
    echo
    echo "## ${entry#*|}"
    scontrol show job "${entry%%|*}"
  done
  echo "## Slurm's job completion log (jobcomp/filetxt)"
  cat "$SEQMASSAGE_SLURM_DIR/jobcomp.txt"
} >"$work/scheduler-record.txt"
for entry in "${recorded[@]}"; do
  scontrol show job -o "${entry%%|*}" | while read -r line; do
    echo "  ${entry#*|}: $(tr ' ' '\n' <<<"$line" | grep -E '^(JobId|ArrayTaskId|JobState|Reason|ExitCode|RunTime|TimeLimit)=' | tr '\n' ' ')"
  done
done
if [ -n "$lock_missing" ]; then
  log "duplicate: NOT CHECKED: no output-folder lock in this build: $lock_missing"
fi
log "passed in $((SECONDS - started)) s (scheduler record: build/slurm-test/scheduler-record.txt)"
