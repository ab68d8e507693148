#!/bin/sh
# A single-node Slurm on this machine (munge, slurmctld, slurmd; Debian's slurm-wlm), for tests of
# `rpvio-bench --executor slurm` and for trying it out. Idempotent: installs what is missing,
# writes /etc/slurm/slurm.conf only when absent (or when it is this script's), starts the daemons
# that are not running, and waits until the node accepts jobs. No cgroups needed.
# Exit 0: a partition accepts jobs. Exit 1: the daemons could not start (the reason on stderr).
set -u
say() { echo "start-slurm: $*" >&2; }

if ! command -v slurmctld >/dev/null 2>&1 || ! command -v munged >/dev/null 2>&1; then
  if [ "$(id -u)" != 0 ]; then say "slurm-wlm and munge are not installed (needs root)"; exit 1; fi
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q slurm-wlm munge >/dev/null 2>&1 ||
    { say "apt-get install slurm-wlm munge failed"; exit 1; }
fi

conf=/etc/slurm/slurm.conf
marker="# written by rpvio scripts/start-slurm.sh"
if [ ! -f "$conf" ] || head -1 "$conf" | grep -q "$marker"; then
  node=$(hostname -s)
  cpus=$(nproc)
  memory_mb=$(awk '/MemTotal/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)
  mkdir -p /etc/slurm /var/lib/slurm/slurmctld /var/lib/slurm/slurmd /var/log/slurm
  chown -R slurm:slurm /var/lib/slurm /var/log/slurm 2>/dev/null
  cat >"$conf" <<CONF
$marker
ClusterName=rpvio
SlurmctldHost=$node
SlurmUser=slurm
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MinJobAge=3600
StateSaveLocation=/var/lib/slurm/slurmctld
SlurmdSpoolDir=/var/lib/slurm/slurmd
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
NodeName=$node CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=rpvio Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
fi

if ! pgrep -x munged >/dev/null; then
  mkdir -p /run/munge && chown munge:munge /run/munge
  [ -s /etc/munge/munge.key ] || { say "no /etc/munge/munge.key"; exit 1; }
  runuser -u munge -- /usr/sbin/munged || { say "munged did not start"; exit 1; }
fi
pgrep -x slurmctld >/dev/null || /usr/sbin/slurmctld || { say "slurmctld did not start"; exit 1; }
pgrep -x slurmd >/dev/null || /usr/sbin/slurmd || { say "slurmd did not start"; exit 1; }

# The node is idle (or mixed/allocated) once slurmd has registered.
for _ in $(seq 1 60); do
  state=$(sinfo -h -o %t 2>/dev/null | head -1)
  case "$state" in idle* | mix* | alloc*) exit 0 ;; esac
  case "$state" in down* | drain*) scontrol update nodename="$(hostname -s)" state=resume 2>/dev/null ;; esac
  sleep 1
done
say "the node did not come up (sinfo: '${state:-no answer}'; logs in /var/log/slurm/)"
exit 1
