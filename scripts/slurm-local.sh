#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, for `netspec compare --executor slurm` and
# `netspec city --executor slurm` and their tests: Debian's slurm-wlm and munge (installed with
# apt-get when missing, as root), munged, slurmctld and slurmd started directly (no systemd, no
# cgroups), one partition `debug` with this machine's CPUs. Idempotent; a second `start` takes
# well under a second.
#
#   scripts/slurm-local.sh start    install if needed, start what is not running, wait until
#                                   the node takes jobs; prints `SLURM_CONF=<path>` last
#   scripts/slurm-local.sh stop     stop slurmd, slurmctld and munged (by their pidfiles)
#   scripts/slurm-local.sh status   exit 0 when the cluster takes jobs
#   scripts/slurm-local.sh conf     print the path of its slurm.conf
#
# Slurm's commands find the cluster through SLURM_CONF (this script never writes /etc/slurm):
#   export SLURM_CONF=$(scripts/slurm-local.sh conf)
# Files (configuration, state, spool, logs, pidfiles) live in $NETSPEC_SLURM_DIR, by default
# ~/.cache/netspec/slurm.
set -euo pipefail
DIR=${NETSPEC_SLURM_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/netspec/slurm}
CONF=$DIR/slurm.conf
log() { printf '[slurm-local] %s\n' "$*" >&2; }
die() { printf '[slurm-local] ERROR: %s\n' "$*" >&2; exit 1; }

# Whether the process in pidfile $1 is alive and named $2.
alive() {
  [[ -s $1 ]] || return 1
  local pid; pid=$(cat "$1")
  [[ $pid =~ ^[0-9]+$ ]] && [[ -r /proc/$pid/comm ]] && [[ $(cat "/proc/$pid/comm") == "$2" ]]
}

install_packages() {
  command -v slurmctld >/dev/null && command -v slurmd >/dev/null && command -v munged >/dev/null && return
  [[ $(id -u) -eq 0 ]] || die "slurm-wlm and munge are not installed; run this script as root (it installs them with apt-get)"
  log "installing Debian packages: slurm-wlm munge"
  export DEBIAN_FRONTEND=noninteractive
  if ! apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null 2>&1; then
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null
  fi
}

# `hostname -s` must resolve for slurmctld and slurmd to find each other.
resolvable_host() {
  local host; host=$(hostname -s)
  getent hosts "$host" >/dev/null || { log "adding $host to /etc/hosts"; echo "127.0.0.1 $host" >>/etc/hosts; }
}

start_munge() {
  mkdir -p /run/munge /var/log/munge /var/lib/munge
  chown munge:munge /run/munge /var/log/munge /var/lib/munge
  chmod 0755 /run/munge
  if [[ ! -s /etc/munge/munge.key ]]; then
    mungekey -c -f -k /etc/munge/munge.key
  fi
  chown munge:munge /etc/munge/munge.key
  chmod 0600 /etc/munge/munge.key
  if ! alive /run/munge/munged.pid munged; then
    runuser -u munge -- /usr/sbin/munged 9>&-
  fi
  for _ in $(seq 50); do
    munge -n 2>/dev/null | unmunge >/dev/null 2>&1 && return
    sleep 0.1
  done
  die "munged does not answer (munge -n | unmunge fails); see /var/log/munge/munged.log"
}

write_conf() {
  local host node mem
  host=$(hostname -s)
  mkdir -p "$DIR/state" "$DIR/spool" "$DIR/log"
  # The node's CPUs and topology as slurmd sees them; memory a little below what it reports.
  node=$(slurmd -C | head -n1)
  mem=$(sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' <<<"$node")
  node=$(sed "s/RealMemory=[0-9]*/RealMemory=$((mem * 95 / 100))/; s/UpTime=.*//" <<<"$node")
  cat >"$CONF.tmp" <<CONF
# Written by scripts/slurm-local.sh: a single-node cluster for netspec's tests.
ClusterName=netspec
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerParameters=batch_sched_delay=0
DependencyParameters=kill_invalid_depend
ReturnToService=2
MinJobAge=3600
KillWait=5
MailProg=/bin/true
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
$node
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  mv "$CONF.tmp" "$CONF"
}

# Waits until the controller answers and the node is idle or busy (not down or drained).
wait_ready() {
  local host state
  host=$(hostname -s)
  for _ in $(seq 150); do
    if scontrol ping 2>/dev/null | grep -q 'is UP'; then
      state=$(sinfo -h -n "$host" -o %t 2>/dev/null | head -n1 || true)
      case $state in
        idle|mix|alloc|comp) return 0 ;;
        down*|drain*|drng*|fail*) scontrol update NodeName="$host" State=RESUME >/dev/null 2>&1 || true ;;
      esac
    fi
    sleep 0.2
  done
  die "the cluster did not come up in 30 s; see $DIR/log/slurmctld.log and $DIR/log/slurmd.log"
}

start() {
  install_packages
  resolvable_host
  mkdir -p "$DIR"
  exec 9>"$DIR/start.lock"
  flock 9
  start_munge
  local running=0
  alive "$DIR/slurmctld.pid" slurmctld && alive "$DIR/slurmd.pid" slurmd && running=1
  if ((!running)); then
    write_conf
    alive "$DIR/slurmctld.pid" slurmctld || /usr/sbin/slurmctld -f "$CONF" 9>&-
    alive "$DIR/slurmd.pid" slurmd || /usr/sbin/slurmd -f "$CONF" 9>&-
  fi
  export SLURM_CONF=$CONF
  wait_ready
  ((running)) || log "started: partition debug on $(hostname -s)"
  echo "SLURM_CONF=$CONF"
}

stop_one() {
  local pidfile=$1 name=$2 pid
  alive "$pidfile" "$name" || return 0
  pid=$(cat "$pidfile")
  kill "$pid"
  for _ in $(seq 100); do
    [[ -d /proc/$pid ]] || return 0
    sleep 0.1
  done
  die "$name (pid $pid) did not stop in 10 s"
}

case ${1:-} in
  start) start ;;
  stop)
    stop_one "$DIR/slurmd.pid" slurmd
    stop_one "$DIR/slurmctld.pid" slurmctld
    stop_one /run/munge/munged.pid munged
    ;;
  status)
    alive "$DIR/slurmctld.pid" slurmctld && alive "$DIR/slurmd.pid" slurmd \
      && SLURM_CONF=$CONF scontrol ping 2>/dev/null | grep -q 'is UP'
    ;;
  conf) echo "$CONF" ;;
  *) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 2 ;;
esac
