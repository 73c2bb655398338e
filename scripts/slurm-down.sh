#!/usr/bin/env bash
# Stops the single-node Slurm that scripts/slurm-up.sh started: slurmd, slurmctld and
# munged, each by its pid file, waiting until each has exited. Jobs still running are
# killed with slurmd. The configuration and the packages stay; slurm-up.sh starts it
# again.
set -euo pipefail

stop() {
    local name=$1 pidfile=$2
    [[ -f $pidfile ]] || return 0
    local pid
    pid="$(cat "$pidfile")"
    if kill -0 "$pid" 2>/dev/null; then
        echo "slurm-down: stopping $name ($pid)"
        kill "$pid"
        for _ in $(seq 1 100); do
            kill -0 "$pid" 2>/dev/null || break
            sleep 0.1
        done
        if kill -0 "$pid" 2>/dev/null; then
            echo "slurm-down: $name ($pid) did not stop within 10 s" >&2
            return 1
        fi
    fi
    rm -f "$pidfile"
}

stop slurmd /run/slurm/slurmd.pid
stop slurmctld /run/slurm/slurmctld.pid
stop munged /run/munge/munged.pid
echo "slurm-down: stopped"
