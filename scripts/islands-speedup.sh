#!/usr/bin/env bash
# The speed of one island search on one process and on two: the paper's tree sketch,
# K islands of the published population, a fixed number of generations, run as
#   one process with one worker thread,
#   one process with two worker threads,
#   mpirun -n 2, one worker thread per process,
# each REPEATS times, interleaved, so that a change in the machine's load touches every
# configuration alike. Every run must end with the same best fitness (the islands'
# result does not depend on the number of processes or threads). Prints, for every run,
# the whole command's wall time and the seconds per generation over the second half of
# the run (from fitness.csv's elapsed_s: the search alone, after the first generation's
# full evaluations), the medians per configuration, and the load average.
#
# Usage: scripts/islands-speedup.sh [OUT_DIR]   (default target/islands-speedup)
# Environment: K (islands, default 4), GENERATIONS (default 60), REPEATS (default 3).
# Needs a build with the `mpi` feature, OpenMPI's mpirun and jq.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
command -v jq >/dev/null || { echo "jq is needed to read the summaries" >&2; exit 1; }
command -v mpirun >/dev/null || { echo "mpirun (OpenMPI) is needed" >&2; exit 1; }

out="${1:-target/islands-speedup}"
k="${K:-4}"
generations="${GENERATIONS:-60}"
repeats="${REPEATS:-3}"
cargo build --release --quiet --features mpi
bin=./target/release/shapegen
scene=scenes/paper/tree_sketch1.toml
args=(run "$scene" --cpu --seed 1 --islands "$k" --generations "$generations")
mpi=(mpirun -n 2 --oversubscribe)
if [[ $(id -u) == 0 ]]; then
    mpi+=(--allow-run-as-root)
fi

# Runs configuration $1 once into $2 and prints its wall time in seconds.
run_once() {
    local start end
    start=$(date +%s.%N)
    case "$1" in
        1p1t) "$bin" --threads 1 "${args[@]}" --out "$2" >/dev/null 2>&1 ;;
        1p2t) "$bin" --threads 2 "${args[@]}" --out "$2" >/dev/null 2>&1 ;;
        2p1t) "${mpi[@]}" "$bin" --threads 1 "${args[@]}" --out "$2" >/dev/null 2>&1 ;;
    esac
    end=$(date +%s.%N)
    awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }'
}

declare -A times pergen
best=""
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq 1 "$repeats"); do
    for config in 1p1t 1p2t 2p1t; do
        dir="$out/$config-$r"
        rm -rf "$dir"
        t=$(run_once "$config" "$dir")
        fitness=$(jq -r .best_fitness "$dir/summary.json")
        if [[ -z "$best" ]]; then best="$fitness"; fi
        if [[ "$fitness" != "$best" ]]; then
            echo "$config run $r ended at $fitness, not $best" >&2
            exit 1
        fi
        per=$(awk -F, -v half=$((generations / 2)) -v last="$generations" '
            $1 == half { a = $2 } $1 == last { b = $2 }
            END { printf "%.3f", (b - a) / (last - half) }' "$dir/fitness.csv")
        times[$config]+="$t "
        pergen[$config]+="$per "
        echo "$config run $r: ${t} s in all, ${per} s per generation (load $(cut -d' ' -f1 /proc/loadavg))"
    done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
median() { tr ' ' '\n' | grep . | sort -g | awk '{ x[NR] = $1 } END { print x[int((NR + 1) / 2)] }'; }
echo "| configuration | whole command, s | per generation, s (median of $repeats) |"
echo "|---|---:|---:|"
for config in 1p1t 1p2t 2p1t; do
    echo "| $config | $(echo "${times[$config]}" | median) | $(echo "${pergen[$config]}" | median) |"
done
echo "every run ended at best fitness $best"
