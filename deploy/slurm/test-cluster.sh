#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for the Slurm executor's tests (ctest label "slurm").
#   bash deploy/slurm/test-cluster.sh start DIR   installs slurmctld, slurmd, slurm-client and munge
#                                                 (Debian 12), writes DIR/slurm.conf, starts the daemons
#   bash deploy/slurm/test-cluster.sh stop DIR    stops them
# Commands then need SLURM_CONF=DIR/slurm.conf. Runs as root, without systemd (daemons started
# directly; no cgroups: proctrack/linuxproc, task/none), so it also works in containers and CI.
set -euo pipefail
action="${1:?usage: test-cluster.sh start|stop DIR}"
D="$(mkdir -p "${2:?usage: test-cluster.sh start|stop DIR}" && cd "$2" && pwd)"
export SLURM_CONF="$D/slurm.conf"

stop() {
  for p in "$D/slurmd.pid" "$D/slurmctld.pid" "$D/munged.pid"; do
    if [ -f "$p" ]; then kill "$(cat "$p")" 2>/dev/null || true; rm -f "$p"; fi
  done
}

if [ "$action" = stop ]; then stop; exit 0; fi
[ "$action" = start ] || { echo "usage: test-cluster.sh start|stop DIR" >&2; exit 2; }

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
missing=()
for p in slurmctld slurmd slurm-client munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

stop
mkdir -p "$D/state" "$D/spool"
cpus=$(nproc)
cat > "$SLURM_CONF" <<CONF
ClusterName=rupture-test
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/slurmctld.pid
SlurmdPidFile=$D/slurmd.pid
SlurmctldLogFile=$D/slurmctld.log
SlurmdLogFile=$D/slurmd.log
SlurmctldPort=${RUPTURE_SLURMCTLD_PORT:-6817}
SlurmdPort=${RUPTURE_SLURMD_PORT:-6818}
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
MinJobAge=3600
KillWait=5
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=1000 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
mkdir -p /run/munge
chown munge:munge /run/munge 2>/dev/null || true
if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
  runuser -u munge -- /usr/sbin/munged --pid-file="$D/munged.pid" 2>/dev/null || \
    runuser -u munge -- /usr/sbin/munged
fi
slurmctld -i
slurmd -N localhost
for _ in $(seq 1 100); do
  sinfo -h -N -o %T 2>/dev/null | grep -qE '^(idle|mixed)' && { echo "slurm test cluster up ($SLURM_CONF)"; exit 0; }
  sleep 0.2
done
echo "slurm test cluster did not come up; logs in $D" >&2
exit 1
