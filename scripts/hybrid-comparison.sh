#!/usr/bin/env bash
# The hybrid against the paper's four methods (GA, SMC, SOSMC, RJMCMC) at equal wall
# time, on the paper's three scenes and the project's six reachable targets, at three
# budgets per scene, RUNS seeds each.
#
# Usage: scripts/hybrid-comparison.sh [OUT_DIR]      (default target/hybrid-comparison)
# Environment: RUNS (runs per method, default 10), SEED (base seed, default 1), SCENES
# (a space-separated subset of the scene names below), BUDGETS (seconds per run, in
# place of each scene's own three), METHODS (default ga,smc,sosmc,rjmcmc,hybrid).
#
# Each scene's budgets, on the quiet 2-core machine of benches/README.md, in the GA's
# evaluations against the original's own budget for the scene's generator (the
# spaceship's 130 generations, 15.75 k evaluations; the city's 30, 7.1 k; the tree's
# 255 k):
#   spaceships 0.3, 3 and 60 s: about 0.5, 4.7 and 90 times the original's
#   cities     0.5, 5 and 50 s: about 1.2, 12 and 150 times
#   trees      10, 100 and 1000 s: about 0.09, 0.77 and 8 times
# The whole matrix takes about RUNS * 5 * (sum of all budgets, 3.7 k s) seconds: some
# 51 hours at 10 runs, the trees' 1000 s alone 42 of them; run it in parts (SCENES,
# BUDGETS, METHODS).
#
# Writes each comparison to OUT_DIR/SCENE-SECONDSs and prints the rows of the table in
# benches/README.md (median and quartiles of the final best; for scenes with an
# optimum, the runs that reached 90 %, 99 % and 99.9 % of it).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
out="${1:-target/hybrid-comparison}"
runs="${RUNS:-10}"
seed="${SEED:-1}"
methods="${METHODS:-ga,smc,sosmc,rjmcmc,hybrid}"
declare -A budgets=(
    [paper/spaceship_volume]="0.3 3 60"
    [paper/city_whale]="0.5 5 50"
    [paper/tree_sketch1]="10 100 1000"
    [spaceship_fill]="0.3 3 60"
    [spaceship_fill2]="0.3 3 60"
    [city_skyline]="0.5 5 50"
    [city_whale_view]="0.5 5 50"
    [tree_sketch]="10 100 1000"
    [tree_sketch2]="10 100 1000"
)
scenes="${SCENES:-paper/spaceship_volume paper/city_whale paper/tree_sketch1 spaceship_fill spaceship_fill2 city_skyline city_whale_view tree_sketch tree_sketch2}"

for scene in $scenes; do
    [[ -v budgets[$scene] ]] || { echo "unknown scene $scene: one of ${!budgets[*]}" >&2; exit 2; }
done
command -v jq >/dev/null || { echo "jq is needed to print the table" >&2; exit 1; }
cargo build --release --quiet
mkdir -p "$out"
for scene in $scenes; do
    for seconds in ${BUDGETS:-${budgets[$scene]}}; do
        dir="$out/$(basename "$scene")-${seconds}s"
        echo "== $scene: $runs runs per method, $seconds s each (load: $(cut -d' ' -f1-3 /proc/loadavg))" >&2
        ./target/release/shapegen compare "scenes/$scene.toml" --cpu \
            --methods "$methods" --runs "$runs" --seconds "$seconds" \
            --seed "$seed" --out "$dir"
        jq -r --arg scene "$(basename "$scene")" '.seconds as $s | .methods[] |
            "| \($scene) | \($s) | \(.method) | \(.final_quartiles[1] * 1000 | round / 1000) | \(.final_quartiles[0] * 1000 | round / 1000) .. \(.final_quartiles[2] * 1000 | round / 1000) | \(if .targets then ([.targets[] | "\(.reached)"] | join(" / ")) else "" end) | \(.evaluations | round) |"' \
            "$dir/summary.json"
    done
done
