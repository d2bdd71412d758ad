#!/usr/bin/env bash
# A private single-node Slurm cluster on this machine, for the cluster tests and benchmarks: one
# node with this machine's cores and memory, one partition, its own munged, slurmctld and slurmd,
# all under one state folder, on ports no other daemon uses.
#
#   bash tools/slurm_local.sh start              install what is missing (apt-get: slurm-wlm,
#                                                munge), start the daemons, wait for the node idle
#   eval "$(bash tools/slurm_local.sh env)"      point sbatch, squeue, scontrol, scancel at it
#   bash tools/slurm_local.sh status             the daemons and the node, exit 1 if not running
#   bash tools/slurm_local.sh stop               cancel its jobs, end the daemons it started (by
#                                                their pid files), remove the state folder
#
# The state folder is $SEQMASSAGE_SLURM_DIR, by default /tmp/seqmassage-slurm-<uid>-<checkout>
# (one cluster per checkout). It holds slurm.conf, the munge key and socket, the daemons' pid
# files and logs (log/), the controller's state and the node's spool, and jobcomp.txt: Slurm's
# record of every finished job (jobcomp/filetxt; there is no accounting database, so no sacct).
# Finished jobs stay in `scontrol show job` for an hour (MinJobAge).
#
# start is safe to run again: a running cluster is kept; leftovers of an earlier one (daemons
# gone, state left behind) are cleared first. stop and a restart only ever signal a process whose
# pid is in one of the state folder's pid files and whose command line names the state folder,
# so no other Slurm or munge daemon on the machine is touched.
#
# Debian 12's Slurm 22.05, as root: ProctrackType=proctrack/linuxproc and TaskPlugin=task/none
# (no cgroups needed), no accounting, KillWait=30 (SIGTERM, then SIGKILL 30 s later), and
# batch_sched_delay=0: a job starts at the controller's next second (by default a batch job
# submitted soon after another waited about 3 s).
# Exit status: 0 done; 1 the cluster did not start (the logs' ends are printed); 2 usage;
# 3 Slurm or munge is missing and cannot be installed here (the tests then skip).
set -euo pipefail
export PATH="$PATH:/usr/sbin:/sbin" # the daemons
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
state=${SEQMASSAGE_SLURM_DIR:-/tmp/seqmassage-slurm-$(id -u)-$(printf '%s' "$root" | cksum | cut -d' ' -f1)}
marker="$state/.seqmassage-slurm-local"
conf="$state/slurm.conf"
socket="$state/munge/munge.socket"
daemons=(munged slurmctld slurmd)

say() { echo "slurm_local: $*" >&2; }

usage() {
  echo "usage: bash $0 start|stop|status|env" >&2
  exit 2
}

# --- Installing ------------------------------------------------------------------------------

have_commands() {
  local c
  for c in munged munge slurmctld slurmd sbatch squeue scontrol scancel sinfo; do
    command -v "$c" >/dev/null 2>&1 || return 1
  done
}

install_missing() {
  have_commands && return 0
  local sudo="" policy=/usr/sbin/policy-rc.d made_policy=0 status=0
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  if ! command -v apt-get >/dev/null 2>&1; then
    say "Slurm or munge is missing and there is no apt-get to install them"
    exit 3
  fi
  say "installing slurm-wlm and munge (apt-get)"
  export DEBIAN_FRONTEND=noninteractive
  # The packages would start the system's munge (and try slurmd, slurmctld) on installation:
  # not wanted, ours run under the state folder. policy-rc.d 101 is Debian's "do not start".
  if [ ! -e "$policy" ]; then
    printf '#!/bin/sh\nexit 101\n' | $sudo tee "$policy" >/dev/null && $sudo chmod 755 "$policy" &&
      made_policy=1
  fi
  { $sudo apt-get update -qq &&
    $sudo apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null; } || status=$?
  [ "$made_policy" = 0 ] || $sudo rm -f "$policy"
  if [ "$status" != 0 ]; then
    say "could not install slurm-wlm and munge (apt-get status $status)"
    exit 3
  fi
  have_commands || {
    say "slurm-wlm and munge installed, but their commands are not found"
    exit 3
  }
}

# --- The daemons we started ------------------------------------------------------------------

# The pid in the daemon's pid file if that process is alive and is ours: its command line names
# the state folder (a recycled pid, or another cluster's daemon, is not).
our_pid() {  # our_pid NAME
  local file="$state/$1.pid" pid
  [ -f "$file" ] || return 1
  pid=$(tr -dc '0-9' <"$file")
  [ -n "$pid" ] && [ -r "/proc/$pid/cmdline" ] || return 1
  tr '\0' ' ' <"/proc/$pid/cmdline" | grep -qF -- "$state" || return 1
  echo "$pid"
}

running() {
  local d
  for d in "${daemons[@]}"; do our_pid "$d" >/dev/null || return 1; done
}

node_state() { SLURM_CONF=$conf sinfo -h -N -o '%t' 2>/dev/null | head -n1; }

wait_for() {  # wait_for SECONDS COMMAND...: poll every 0.2 s until COMMAND succeeds
  local deadline=$((SECONDS + $1))
  shift
  until "$@"; do
    [ "$SECONDS" -lt "$deadline" ] || return 1
    sleep 0.2
  done
}

node_idle() { [ "$(node_state)" = idle ]; }
no_jobs() { [ -z "$(SLURM_CONF=$conf squeue -h -o '%i' 2>/dev/null)" ]; }
# Gone, or a zombie nobody reaps (where pid 1 does not; kill -0 still succeeds on it).
gone() { [ ! -e "/proc/$1" ] || [ "$(sed 's/^.*) //' "/proc/$1/stat" 2>/dev/null | cut -c1)" = Z ]; }

# Ends the daemon NAME if it is ours: SIGTERM, then SIGKILL after 20 s.
end_daemon() {
  local pid
  pid=$(our_pid "$1") || return 0
  kill -TERM "$pid" 2>/dev/null || return 0
  if ! wait_for 20 gone "$pid"; then
    say "$1 (pid $pid) still running 20 s after SIGTERM: SIGKILL"
    kill -KILL "$pid" 2>/dev/null || true
    wait_for 5 gone "$pid" || true
  fi
}

# Cancels the cluster's jobs (their processes end through slurmd: SIGTERM, then SIGKILL after
# KillWait), ends our three daemons, removes the state folder.
stop_cluster() {
  if our_pid slurmctld >/dev/null && our_pid slurmd >/dev/null; then
    if ! no_jobs; then
      say "cancelling the cluster's jobs"
      SLURM_CONF=$conf scancel --partition=local 2>/dev/null || true
      wait_for 60 no_jobs || say "jobs still listed 60 s after scancel"
    fi
  fi
  local d
  for d in slurmd slurmctld munged; do end_daemon "$d"; done
  if [ -d "$state" ]; then
    if [ -f "$marker" ]; then
      rm -rf "$state"
    else
      say "$state is not a state folder of this script (no $(basename "$marker")): left alone"
    fi
  fi
}

# --- Starting --------------------------------------------------------------------------------

port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }

# Two consecutive free ports, starting from one derived from the state folder's name.
choose_ports() {
  local p=$((20000 + $(printf '%s' "$state" | cksum | cut -d' ' -f1) % 20000))
  local tries=0
  until port_free "$p" && port_free $((p + 1)); do
    p=$((p + 2))
    [ "$p" -lt 65000 ] || p=20000
    tries=$((tries + 1))
    [ "$tries" -lt 2000 ] || {
      say "no two free ports found"
      exit 1
    }
  done
  echo "$p"
}

write_conf() {
  local port=$1 host hardware memory user
  host=$(hostname -s)
  # slurmd -C prints this machine's node line (CPUs, boards, sockets, cores, threads, memory);
  # RealMemory a little below what it finds, so that the node never registers with less.
  hardware=$(slurmd -C | head -n1)
  [[ $hardware == NodeName=*RealMemory=* ]] || {
    say "slurmd -C printed no node line: $hardware"
    exit 1
  }
  hardware=${hardware#NodeName=* }
  memory=$(sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' <<<"$hardware")
  hardware=${hardware/RealMemory=$memory/RealMemory=$((memory * 95 / 100))}
  user=$(id -un)
  cat >"$conf" <<EOF
# Written by tools/slurm_local.sh: a private single-node cluster (state in $state).
ClusterName=seqmassage
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$state/jobcomp.txt
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerParameters=batch_sched_delay=0
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
KillWait=30
OverTimeLimit=0
MinJobAge=3600
NodeName=$host NodeAddr=127.0.0.1 $hardware State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}

print_logs() {
  local f
  for f in "$state"/log/*.log; do
    [ -f "$f" ] || continue
    echo "--- $f (last 15 lines)" >&2
    tail -n 15 "$f" >&2
  done
}

fail_start() {
  say "$1"
  print_logs
  stop_cluster
  exit 1
}

start_cluster() {
  install_missing
  if [ -f "$marker" ] && running; then
    if wait_for 30 node_idle_or_busy; then
      say "already running ($conf)"
      return 0
    fi
    say "the daemons run but the node is $(node_state || echo unknown): restarting"
  fi
  [ -e "$state" ] && [ ! -f "$marker" ] && [ -n "$(ls -A "$state" 2>/dev/null)" ] && {
    say "$state exists and is not this script's state folder; set SEQMASSAGE_SLURM_DIR"
    exit 1
  }
  stop_cluster # leftovers of an earlier cluster: its daemons (if ours) and its state
  # munged wants its socket's folders open to all (execute) and its key's folder private.
  mkdir -p "$state"
  chmod 755 "$state"
  : >"$marker"
  mkdir -p "$state/munge" "$state/key" "$state/log" "$state/ctld" "$state/spool"
  chmod 755 "$state/munge"
  chmod 700 "$state/key"
  local port
  port=$(choose_ports)
  write_conf "$port"

  # munged: its own key, socket, pid, seed and log files.
  if command -v mungekey >/dev/null 2>&1; then
    mungekey --create --keyfile="$state/key/munge.key" >/dev/null 2>&1
  else
    dd if=/dev/urandom of="$state/key/munge.key" bs=1024 count=1 status=none
  fi
  chmod 400 "$state/key/munge.key"
  munged --socket="$socket" --key-file="$state/key/munge.key" \
    --pid-file="$state/munged.pid" --log-file="$state/log/munged.log" \
    --seed-file="$state/key/munged.seed" >/dev/null 2>&1 ||
    fail_start "munged did not start"
  wait_for 10 munge_works || fail_start "munged does not answer on $socket"

  SLURM_CONF=$conf slurmctld -f "$conf" >/dev/null 2>&1 || fail_start "slurmctld did not start"
  wait_for 20 our_pid slurmctld >/dev/null || fail_start "slurmctld wrote no pid file"
  SLURM_CONF=$conf slurmd -f "$conf" >/dev/null 2>&1 || fail_start "slurmd did not start"
  wait_for 20 our_pid slurmd >/dev/null || fail_start "slurmd wrote no pid file"
  wait_for 60 node_idle || fail_start "the node is not idle after 60 s (it is: $(node_state))"
  say "running: $(SLURM_CONF=$conf sinfo -h -N -o '%N %c CPUs, %m MB, %t') ($conf)"
}

munge_works() { munge -n -S "$socket" 2>/dev/null | unmunge -S "$socket" >/dev/null 2>&1; }
node_idle_or_busy() { [[ "$(node_state)" =~ ^(idle|mix|alloc)$ ]]; }

[ $# -eq 1 ] || usage
case "$1" in
  start) start_cluster ;;
  stop)
    stop_cluster
    say "stopped"
    ;;
  status)
    if [ -f "$marker" ] && running; then
      for d in "${daemons[@]}"; do echo "$d: pid $(our_pid "$d")"; done
      echo "node: $(node_state)"
      echo "SLURM_CONF=$conf"
    else
      echo "not running (state folder $state)"
      exit 1
    fi
    ;;
  env)
    if [ ! -f "$conf" ]; then
      say "no cluster (no $conf): run 'bash $0 start' first"
      exit 1
    fi
    printf 'export SLURM_CONF=%q\n' "$conf"
    ;;
  *) usage ;;
esac
