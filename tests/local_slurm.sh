# A Slurm of one node on this machine, for tests/farm_slurm_test.sh and
# bench/farm_throughput.sh (sourced): munged, slurmctld and slurmd started in
# the foreground of background jobs, with their key, sockets, state, ports
# and logs private to WORK, and stopped when the script exits. Exits 77
# (skipped) without Slurm and munge (scripts/install-deps.sh) or when not
# root (the daemons run as the user who starts them; munged and slurmd want
# root). Exports SLURM_CONF for sbatch, squeue and relight farm.
#   start_local_slurm WORK CPUS     then     wait_for_job JOB_ID SECONDS

start_local_slurm() {
  local work=$1 cpus=$2 program
  for program in munged slurmctld slurmd sbatch squeue sinfo; do
    command -v "$program" >/dev/null || { echo "skipped: $program is not installed (scripts/install-deps.sh)"; exit 77; }
  done
  [ "$(id -u)" = 0 ] || { echo "skipped: Slurm's daemons are started as root here"; exit 77; }
  rm -rf "$work"
  mkdir -p "$work"/{munge,state,spool,log}
  chmod 700 "$work/munge"
  local_slurm_daemons=()
  trap stop_local_slurm EXIT

  head -c 1024 /dev/urandom >"$work/munge/munge.key"
  chmod 400 "$work/munge/munge.key"
  munged --force --foreground --key-file="$work/munge/munge.key" --socket="$work/munge/socket" \
    --pid-file="$work/munge/munged.pid" --log-file="$work/log/munged.log" --seed-file="$work/munge/seed" \
    2>>"$work/log/munged.err" &
  local_slurm_daemons+=($!)

  local host port
  host=$(hostname -s)
  port=$((20000 + RANDOM % 20000))
  export SLURM_CONF="$work/slurm.conf"
  cat >"$SLURM_CONF" <<CONF
ClusterName=relighttest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=relight Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  local i
  for i in $(seq 50); do [ -S "$work/munge/socket" ] && break; sleep 0.1; done
  slurmctld -D -i -f "$SLURM_CONF" 2>>"$work/log/slurmctld.err" &
  local_slurm_daemons+=($!)
  slurmd -D -f "$SLURM_CONF" -N "$host" 2>>"$work/log/slurmd.err" &
  local_slurm_daemons+=($!)
  local_slurm_logs="$work/log"
  for i in $(seq 100); do
    sinfo -h -o %T 2>/dev/null | grep -q idle && return 0
    sleep 0.2
  done
  echo "Slurm did not come up:"
  tail -20 "$work"/log/*
  exit 1
}

stop_local_slurm() {
  local pid
  for pid in "${local_slurm_daemons[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
}

# Waits until job JOB_ID has left the queue (fails after SECONDS).
wait_for_job() {
  local i
  for i in $(seq $(($2 * 5))); do
    [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0
    sleep 0.2
  done
  echo "job $1 still queued after $2 s"
  squeue
  tail -20 "$local_slurm_logs"/*
  exit 1
}
