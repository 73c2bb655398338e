#!/usr/bin/env bash
# Brings up a single-node Slurm on this machine, from nothing: installs Debian's
# `slurm-wlm` and `munge` when missing, starts munge, writes /etc/slurm/slurm.conf for
# this one node (no cgroups, no accounting, no systemd needed), starts slurmctld and
# slurmd, and waits until the controller answers and the node is idle. For Debian 12
# as root.
#
# Usage: scripts/slurm-up.sh          (a second call finds Slurm up and does nothing)
#        scripts/slurm-down.sh        stops what this started
#
# Then `sbatch`, `squeue` and `sinfo` work, e.g. the study of the README's "Parameter
# studies": `sbatch DIR/sweep.sbatch`. Logs: /var/log/slurm/ and /var/log/munge/.
set -euo pipefail

conf=/etc/slurm/slurm.conf
# The first line of a slurm.conf this script wrote; another is never overwritten.
marker="# Written by shapegen's scripts/slurm-up.sh: a single-node Slurm."
wait_s=60

log() { echo "slurm-up: $*"; }
fail() {
    echo "slurm-up: $*" >&2
    exit 1
}

node_state() { sinfo -h -o %t 2>/dev/null | head -n 1; }
controller_up() { scontrol ping 2>/dev/null | grep -q "is UP"; }

if command -v scontrol >/dev/null && controller_up && [[ "$(node_state)" =~ ^(idle|mix|alloc)$ ]]; then
    log "Slurm is already up (node $(hostname -s): $(node_state))"
    exit 0
fi

[[ $(id -u) -eq 0 ]] || fail "run me as root: the daemons run as root and munge as its own user"

if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v munged >/dev/null; then
    log "installing slurm-wlm and munge"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    # Installing prints "policy-rc.d denied execution of start": the daemons are started below.
    apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null
fi

# munge: the package made the key; the daemon runs as the munge user.
if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
    [[ -s /etc/munge/munge.key ]] || fail "/etc/munge/munge.key is missing (reinstall munge)"
    mkdir -p /run/munge /var/log/munge /var/lib/munge
    chown munge:munge /run/munge /var/log/munge /var/lib/munge
    chmod 0755 /run/munge
    log "starting munged"
    runuser -u munge -- /usr/sbin/munged
    for _ in $(seq 1 50); do
        munge -n 2>/dev/null | unmunge >/dev/null 2>&1 && break
        sleep 0.1
    done
    munge -n | unmunge >/dev/null || fail "munge does not work; see /var/log/munge/munged.log"
fi

host="$(hostname -s)"
if [[ -f $conf ]] && [[ "$(head -n 1 "$conf")" != "$marker" ]]; then
    fail "$conf exists and was not written by this script; move it away to use this one"
fi
# The node's CPUs and memory as slurmd sees them, e.g.
# `NodeName=vm CPUs=2 Boards=1 SocketsPerBoard=1 CoresPerSocket=2 ThreadsPerCore=1 RealMemory=24105`.
node="$(slurmd -C | head -n 1)"
[[ $node == "NodeName=$host "* ]] || fail "slurmd -C printed \"$node\", not a line for node $host"
mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd /run/slurm /var/log/slurm
cat >"$conf.tmp" <<EOF
$marker
ClusterName=shapegen
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MailProg=/bin/true
# Without it each wave of short array tasks waits about 3 s.
SchedulerParameters=batch_sched_delay=0
ReturnToService=2
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=/run/slurm/slurmctld.pid
SlurmdPidFile=/run/slurm/slurmd.pid
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=main Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
mv "$conf.tmp" "$conf"

# A daemon runs when its pid file names a live process.
running() { [[ -f $1 ]] && kill -0 "$(cat "$1")" 2>/dev/null; }
if ! running /run/slurm/slurmctld.pid; then
    log "starting slurmctld"
    /usr/sbin/slurmctld
fi
if ! running /run/slurm/slurmd.pid; then
    log "starting slurmd"
    /usr/sbin/slurmd
fi

for _ in $(seq 1 $((wait_s * 5))); do
    if controller_up; then
        case "$(node_state)" in
            idle | mix | alloc)
                log "Slurm is up: node $host $(node_state), partition main"
                exit 0
                ;;
            down* | drain* | drng*)
                scontrol update NodeName="$host" State=RESUME 2>/dev/null || true
                ;;
        esac
    fi
    sleep 0.2
done
fail "Slurm did not come up within $wait_s s (controller: $(scontrol ping 2>&1 | tail -n 1); node: $(node_state)); see /var/log/slurm/"
