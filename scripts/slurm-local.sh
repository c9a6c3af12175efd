#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, for the interoperability test of
# `skyforge study slurm` (sim/tests/interop_slurm.rs). Uses Debian's slurm-wlm and munge
# (scripts/deps.sh installs them), needs root, no systemd, no accounting.
#   scripts/slurm-local.sh start DIR   write DIR/slurm.conf; start munged (unless running),
#                                      slurmctld and slurmd; wait until the node is idle
#   scripts/slurm-local.sh stop DIR    stop what start started
# Clients then need SLURM_CONF=DIR/slurm.conf.
set -euo pipefail
cmd=${1:?start or stop}
dir=$(realpath -m "${2:?state directory}")
export SLURM_CONF="$dir/slurm.conf"

stop() {
  for d in slurmd slurmctld; do
    [ -f "$dir/$d.pid" ] && kill "$(cat "$dir/$d.pid")" 2>/dev/null || true
  done
  if [ -f "$dir/munged.started" ]; then
    pkill -x munged 2>/dev/null || true
    rm -f "$dir/munged.started"
  fi
}

case "$cmd" in
  start)
    mkdir -p "$dir/state" "$dir/spool"
    host=$(hostname -s)
    cpus=$(nproc)
    cat > "$SLURM_CONF" <<CONF
# Written by scripts/slurm-local.sh: one node, this machine.
ClusterName=skyforge-local
SlurmctldHost=$host
AuthType=auth/munge
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
ReturnToService=2
MpiDefault=none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
    if ! pgrep -x munged >/dev/null; then
      mkdir -p /run/munge && chown munge:munge /run/munge
      [ -f /etc/munge/munge.key ] || { echo "slurm-local: no /etc/munge/munge.key (is munge installed?)" >&2; exit 1; }
      runuser -u munge -- /usr/sbin/munged
      touch "$dir/munged.started"
    fi
    slurmctld
    slurmd
    for _ in $(seq 1 60); do
      if sinfo -h -o %t 2>/dev/null | grep -qx idle; then
        echo "slurm-local: node $host idle; export SLURM_CONF=$SLURM_CONF"
        exit 0
      fi
      sleep 0.5
    done
    echo "slurm-local: the node did not come up; logs in $dir" >&2
    stop
    exit 1
    ;;
  stop) stop ;;
  *) echo "usage: $0 start|stop DIR" >&2; exit 2 ;;
esac
