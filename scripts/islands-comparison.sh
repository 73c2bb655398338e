#!/usr/bin/env bash
# The island model against one population of the same total size, at equal evaluations,
# on the paper's three scenes with their published GA settings: K islands of the
# published population N (elitism E each) against one population of K*N (elitism K*E).
# Both breed K*(N-E) children per generation, so equal generations are equal
# evaluations; the budget is a number of generations, so the results do not depend on
# the machine's speed.
#
# Usage: scripts/islands-comparison.sh [OUT_DIR]   (default target/islands-comparison)
# Environment: K (islands, default 4), RUNS (seeds 1..RUNS, default 5), and generations
# per scene: SPACESHIP_GENERATIONS (default 130, the paper's), CITY_GENERATIONS (100,
# the paper's), TREE_GENERATIONS (300; the paper's 1500 takes K times its budget).
#
# Prints the table of benches/README.md.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

out="${1:-target/islands-comparison}"
k="${K:-4}"
runs="${RUNS:-5}"
declare -A generations=(
    [spaceship_volume]="${SPACESHIP_GENERATIONS:-130}"
    [city_whale]="${CITY_GENERATIONS:-100}"
    [tree_sketch1]="${TREE_GENERATIONS:-300}"
)
# The published GA settings: population and elitism.
declare -A population=([spaceship_volume]=150 [city_whale]=100 [tree_sketch1]=200)
declare -A elitism=([spaceship_volume]=30 [city_whale]=30 [tree_sketch1]=30)

command -v jq >/dev/null || { echo "jq is needed to read the summaries" >&2; exit 1; }
cargo build --release --quiet
bin=./target/release/shapegen

# mean +- sample std of the numbers on standard input, to 3 decimals.
stats() {
    awk '{ x[NR] = $1; s += $1 } END {
        m = s / NR; v = 0; for (i = 1; i <= NR; i++) v += (x[i] - m) ^ 2;
        printf "%.3f +- %.3f", m, (NR > 1 ? sqrt(v / (NR - 1)) : 0) }'
}

echo "| scene | generations | evaluations | $k islands of N | one population of $k N | seconds, islands / one |"
echo "|---|---:|---:|---:|---:|---:|"
for scene in spaceship_volume city_whale tree_sketch1; do
    g="${generations[$scene]}"
    n="${population[$scene]}"
    e="${elitism[$scene]}"
    for seed in $(seq 1 "$runs"); do
        "$bin" run "scenes/paper/$scene.toml" --cpu --seed "$seed" --generations "$g" \
            --islands "$k" --out "$out/$scene/islands-$seed" >/dev/null 2>&1
        "$bin" run "scenes/paper/$scene.toml" --method ga --cpu --seed "$seed" --generations "$g" \
            --set "optimizer.population=$((k * n))" --set "optimizer.elitism=$((k * e))" \
            --out "$out/$scene/one-$seed" >/dev/null 2>&1
    done
    best() { for s in $(seq 1 "$runs"); do jq .best_fitness "$out/$scene/$1-$s/summary.json"; done; }
    secs() { for s in $(seq 1 "$runs"); do jq .elapsed_s "$out/$scene/$1-$s/summary.json"; done | awk '{ s += $1 } END { printf "%.1f", s / NR }'; }
    evaluations=$(jq .evaluations "$out/$scene/islands-1/summary.json")
    echo "| $scene | $g | $evaluations | $(best islands | stats) | $(best one | stats) | $(secs islands) / $(secs one) |"
done
