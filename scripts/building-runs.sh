#!/usr/bin/env bash
# The multi-objective building search measured as the published CGA system was: runs of
# 60 generations of 300 on the project's building scene (top-down footprint match, front
# silhouette match, distinct facets; Pareto ranking), one per seed, reporting for each the
# best top-down match of the initial population and of the final front and the wall
# time, then the average and best over the seeds. (`best_top`, the fifth column of
# history.csv, is the scene's first objective.)
#
# Usage: scripts/building-runs.sh [OUT_DIR]      (default target/building-runs)
# Environment: SEEDS (default "1 2 3 4 5 6 7 8 9 10").
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
command -v jq >/dev/null || { echo "jq is needed to read the summaries" >&2; exit 1; }
out="${1:-target/building-runs}"
seeds="${SEEDS:-1 2 3 4 5 6 7 8 9 10}"
cargo build --release --quiet
mkdir -p "$out"

echo "| seed | best top-down match, generation 0 | after 60 | best front match | most facets | front size | wall time of the run |"
echo "|---:|---:|---:|---:|---:|---:|---:|"
for seed in $seeds; do
    ./target/release/shapegen run scenes/building.toml --seed "$seed" --generations 60 \
        --set optimizer.population=300 --out "$out/seed$seed" 2>/dev/null >/dev/null
    first="$(awk -F, 'NR == 2 { print $5 }' "$out/seed$seed/history.csv")"
    jq -r --arg seed "$seed" --argjson first "$first" '
        (.objectives | map({(.name): .best}) | add) as $b |
        "| \($seed) | \($first * 10000 | round / 10000) | \($b.top * 10000 | round / 10000) | \($b.front * 10000 | round / 10000) | \($b.facets) | \(.front) | \(.elapsed_s * 10 | round / 10) s |"' \
        "$out/seed$seed/summary.json"
done
for seed in $seeds; do cat "$out/seed$seed/summary.json"; done | jq -rs '
    map(.objectives[] | select(.name == "top") | .best) as $top |
    map(.elapsed_s) as $t |
    "top-down match over \($top | length) runs: average \(($top | add / length) * 10000 | round / 10000), best \($top | max * 10000 | round / 10000); wall time per run \(($t | add / length) * 10 | round / 10) s on average"'
