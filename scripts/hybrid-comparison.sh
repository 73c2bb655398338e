#!/usr/bin/env bash
# The hybrid against the paper's four methods (GA, SMC, SOSMC, RJMCMC) at equal wall
# time, on the paper's three scenes and the project's six reachable targets, at budgets
# from about the paper's own up to 100 times it, RUNS seeds each.
#
# Usage: scripts/hybrid-comparison.sh [OUT_DIR]      (default target/hybrid-comparison)
# Environment: RUNS (runs per method, default 10), SEED (base seed, default 1), SCENES
# (a space-separated subset of the scene names below), FACTORS (a subset of
# "1 10 100", the multiples of the base budget to run, default all three).
#
# The base budget of a scene is the wall time its GA takes, on the 2-core machine of
# benches/README.md, for the paper's own evaluation count (the spaceship's and the
# city's 130 and 30 generations); for the trees it is 10 s, since the paper's own tree
# budget (255 k GA evaluations) already takes some 650 s here. The whole matrix takes
# about RUNS * 5 * 111 * (sum of the base budgets, 32.4 s) seconds: some 50 hours at 10 runs,
# so run it in parts (SCENES, FACTORS).
#
# Writes each comparison to OUT_DIR/SCENE-FACTORx and prints the rows of the tables in
# benches/README.md (median and quartiles of the final best; for scenes with an
# optimum, the runs that reached 99 % of it).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
out="${1:-target/hybrid-comparison}"
runs="${RUNS:-10}"
seed="${SEED:-1}"
factors="${FACTORS:-1 10 100}"
declare -A base=(
    [paper/spaceship_volume]=0.3
    [paper/city_whale]=0.5
    [paper/tree_sketch1]=10
    [spaceship_fill]=0.3
    [spaceship_fill2]=0.3
    [city_skyline]=0.5
    [city_whale_view]=0.5
    [tree_sketch]=10
    [tree_sketch2]=10
)
scenes="${SCENES:-paper/spaceship_volume paper/city_whale paper/tree_sketch1 spaceship_fill spaceship_fill2 city_skyline city_whale_view tree_sketch tree_sketch2}"

command -v jq >/dev/null || { echo "jq is needed to print the table" >&2; exit 1; }
cargo build --release --quiet
mkdir -p "$out"
for scene in $scenes; do
    if [[ $scene == paper/* && ! -d ../shared/paper-scenes ]]; then
        echo "skipped $scene: the paper scenes (../shared/paper-scenes) are not beside the repository" >&2
        continue
    fi
    for k in $factors; do
        seconds=$(awk -v b="${base[$scene]}" -v k="$k" 'BEGIN { print b * k }')
        dir="$out/$(basename "$scene")-${k}x"
        echo "== $scene: $runs runs per method, $seconds s each (load: $(cut -d' ' -f1-3 /proc/loadavg))" >&2
        ./target/release/shapegen compare "scenes/$scene.toml" --cpu \
            --methods ga,smc,sosmc,rjmcmc,hybrid --runs "$runs" --seconds "$seconds" \
            --seed "$seed" --out "$dir"
        jq -r --arg scene "$(basename "$scene")" '.seconds as $s | .methods[] |
            "| \($scene) | \($s) | \(.method) | \(.final_quartiles[1] * 1000 | round / 1000) | \(.final_quartiles[0] * 1000 | round / 1000) .. \(.final_quartiles[2] * 1000 | round / 1000) | \(if .targets then "\(.targets[1].reached)/\(.targets[1].runs)" else "" end) | \(.evaluations | round) |"' \
            "$dir/summary.json"
    done
done
