#!/usr/bin/env bash
# Soak: long searches side by side, sampling each process's resident memory and open
# file descriptors every few seconds, to show that memory stays flat once the
# population's models stop growing (docs/reliability.md).
#
# Runs, each for SECONDS (default 1800) on one worker thread:
#   building: scenes/building.toml, the multi-objective GA on three objectives;
#   tree:     scenes/paper/tree_sketch1.toml, the paper's GA with incremental scoring.
# Writes OUT/NAME/ (the run's folder) and OUT/NAME.csv: elapsed_s, rss_kib, fds,
# checkpoint_bytes (the size of the run's checkpoint.json: the population's genomes, a
# measure of how large its models are), then draws OUT/soak.png (scripts/soak-plot.py).
#
# Usage: scripts/soak.sh [OUT_DIR]      (default target/soak)
# Environment: SECONDS_EACH (default 1800), EVERY (sampling period, default 5 s),
#              SHAPEGEN (the binary, default target/release/shapegen, built if missing).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
out="${1:-target/soak}"
seconds="${SECONDS_EACH:-1800}"
every="${EVERY:-5}"
bin="${SHAPEGEN:-target/release/shapegen}"
[ -x "$bin" ] || cargo build --release --quiet
mkdir -p "$out"

# sample PID NAME: one line per period while the process lives.
sample() {
    local pid="$1" name="$2" start
    start="$(date +%s.%N)"
    echo "elapsed_s,rss_kib,fds,checkpoint_bytes" >"$out/$name.csv"
    while kill -0 "$pid" 2>/dev/null; do
        local rss fds ckpt now
        rss="$(awk '/^VmRSS:/ { print $2 }' "/proc/$pid/status" 2>/dev/null || true)"
        fds="$(ls "/proc/$pid/fd" 2>/dev/null | wc -l)"
        ckpt="$(stat -c %s "$out/$name/checkpoint.json" 2>/dev/null || echo 0)"
        now="$(date +%s.%N)"
        [ -n "$rss" ] && printf '%.1f,%s,%s,%s\n' "$(echo "$now - $start" | bc)" "$rss" "$fds" "$ckpt" \
            >>"$out/$name.csv"
        sleep "$every"
    done
}

# run NAME ARGS..: a search in OUT/NAME, replacing an earlier soak's, with its sampler.
run() {
    local name="$1"
    shift
    "$bin" --threads 1 run "$@" --seconds "$seconds" --generations 100000000 --cpu \
        --out "$out/$name" --force >"$out/$name.log" 2>&1 &
    local pid=$!
    sample "$pid" "$name" &
    echo "$name: pid $pid"
}

run building scenes/building.toml
run tree scenes/paper/tree_sketch1.toml
wait
python3 scripts/soak-plot.py "$out/soak.png" "$out/building.csv" "$out/tree.csv"
for name in building tree; do
    echo "== $name ($(tail -n 1 "$out/$name.log"))"
    awk -F, 'NR > 1 { n++; if (n == 1 || $2 < min) min = $2; if ($2 > max) max = $2; last = $2;
                      if ($3 > fds) fds = $3 }
             END { printf "samples %d, RSS min %d KiB, max %d KiB, last %d KiB; at most %d open files\n",
                   n, min, max, last, fds }' "$out/$name.csv"
done
