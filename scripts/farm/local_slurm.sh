#!/usr/bin/env bash
# A throw-away single-node Slurm on this machine, for tests and for trying scripts/farm without
# a cluster. Everything (config, munge key and socket, state, logs, pid files) lives in DIR, the
# daemons listen on 127.0.0.1 only, on free ports, so several can run side by side and nothing
# of the machine's own Slurm or munge is touched.
#   scripts/farm/local_slurm.sh start DIR   # starts munged, slurmctld, slurmd; prints
#                                           # "export SLURM_CONF=DIR/slurm.conf"
#   scripts/farm/local_slurm.sh stop DIR    # stops exactly the daemons that start started (by PID)
# Exit status of start: 0 running, 1 failed (our fault, see DIR/*.log), 77 Slurm cannot run
# here (packages missing, not root, no loopback), with one line saying why.
# Needs root (slurmd runs jobs as their user). No cgroups: proctrack/linuxproc, task/none.
set -euo pipefail

usage() { echo "usage: $0 start|stop DIR" >&2; exit 2; }
[ $# -eq 2 ] || usage
command=$1
dir=$2

# Whether PID runs (an exited daemon whose parent is gone may linger as a zombie until init
# reaps it: that one has stopped).
alive() { kill -0 "$1" 2> /dev/null && ! grep -q '^State:[[:space:]]*Z' "/proc/$1/status" 2> /dev/null; }

stop() {
  # Each daemon by the PID recorded when it started; slurmd first, munged last.
  for name in slurmd slurmctld munged; do
    local file="$dir/$name.started.pid"
    [ -f "$file" ] || continue
    local pid
    pid=$(cat "$file")
    if alive "$pid"; then
      kill -TERM "$pid" 2> /dev/null || true
      for _ in $(seq 100); do alive "$pid" || break; sleep 0.05; done
      if alive "$pid"; then kill -KILL "$pid" 2> /dev/null || true; fi
    fi
    rm -f "$file"
  done
}

skip() { echo "local_slurm: skipped: $*" >&2; exit 77; }

free_port() {
  # A random port in 20000-59999 that nobody on 127.0.0.1 answers on.
  local port
  while :; do
    port=$((20000 + (RANDOM * 32768 + RANDOM) % 40000))
    if ! (exec 3<> "/dev/tcp/127.0.0.1/$port") 2> /dev/null; then echo "$port"; return; fi
  done
}

# Runs "$@" in the background, records its PID in DIR/NAME.started.pid.
start_daemon() {
  local name=$1
  shift
  "$@" > "$dir/$name.out" 2>&1 &
  echo $! > "$dir/$name.started.pid"
}

wait_for() {
  local what=$1 seconds=$2
  shift 2
  for _ in $(seq $((seconds * 10))); do
    if "$@" > /dev/null 2>&1; then return 0; fi
    sleep 0.1
  done
  echo "local_slurm: $what did not come up within ${seconds}s (logs in $dir)" >&2
  return 1
}

case "$command" in
  stop) stop; exit 0 ;;
  start) ;;
  *) usage ;;
esac

for tool in munged mungekey munge unmunge slurmctld slurmd sbatch scontrol sinfo; do
  command -v "$tool" > /dev/null || skip "$tool is not installed (scripts/install-deps.sh installs slurm-wlm and munge)"
done
[ "$(id -u)" -eq 0 ] || skip "a local slurmd must run as root"

mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
# munged refuses keys and sockets in directories others may write to.
chmod 700 "$dir"
mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
chmod 700 "$dir/munge"
trap 'status=$?; if [ $status -ne 0 ]; then stop; fi' EXIT

mungekey --create --keyfile "$dir/munge/munge.key" --force > /dev/null 2>&1 ||
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 2> /dev/null
chmod 600 "$dir/munge/munge.key"
socket="$dir/munge/munge.socket"
start_daemon munged munged --foreground --force --socket="$socket" --key-file="$dir/munge/munge.key" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/munged.seed"
wait_for munged 10 sh -c "munge --socket='$socket' -n | unmunge --socket='$socket'" || exit 1

host=$(hostname -s)
cpus=$(nproc)
ctld_port=$(free_port)
slurmd_port=$(free_port)
cat > "$dir/slurm.conf" << EOF
# Written by scripts/farm/local_slurm.sh: one node, 127.0.0.1 only, no cgroups.
ClusterName=citygen
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
CommunicationParameters=NoCtldInAddrAny,NoInAddrAny
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
MinJobAge=300
KillWait=5
Waittime=0
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$dir/slurm.conf"
# -D: stay in the foreground (so our PID is the daemon's); -i: ignore old state.
start_daemon slurmctld slurmctld -D -i -f "$SLURM_CONF"
wait_for slurmctld 20 scontrol ping || exit 1
start_daemon slurmd slurmd -D -f "$SLURM_CONF" -N "$host"
wait_for "slurmd (node idle)" 30 sh -c "sinfo -h -N -o '%T' | grep -qx idle" || exit 1
trap - EXIT
echo "export SLURM_CONF=$SLURM_CONF"
