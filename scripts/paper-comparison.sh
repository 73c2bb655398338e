#!/usr/bin/env bash
# The paper's comparison of its four search methods (ShapeGenetics, Figures 7 and 9),
# reproduced with `shapegen compare` on the three paper scenes and their published
# settings, every method with the same wall-time budget per run.
#
# Usage: scripts/paper-comparison.sh [OUT_DIR]      (default target/paper-comparison)
# Environment: RUNS (runs per method, default 3), SEED (base seed, default 1), and the
# wall budget per run in seconds: SPACESHIP_SECONDS and CITY_SECONDS (default 20),
# TREE_SECONDS (default 40).
#
# Writes each scene's comparison to OUT_DIR/SCENE,
# copies the pictures to benches/figures/compare-SCENE.png and prints the table rows of
# benches/README.md.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

out="${1:-target/paper-comparison}"
runs="${RUNS:-3}"
seed="${SEED:-1}"
declare -A seconds=(
    [spaceship_volume]="${SPACESHIP_SECONDS:-20}"
    [city_whale]="${CITY_SECONDS:-20}"
    [tree_sketch1]="${TREE_SECONDS:-40}"
)

command -v jq >/dev/null || { echo "jq is needed to print the table" >&2; exit 1; }
cargo build --release --quiet
mkdir -p "$out" benches/figures
for scene in spaceship_volume city_whale tree_sketch1; do
    echo "== $scene: $runs runs per method, ${seconds[$scene]} s each" >&2
    ./target/release/shapegen compare "scenes/paper/$scene.toml" --cpu \
        --methods ga,smc,sosmc,rjmcmc --runs "$runs" --seconds "${seconds[$scene]}" \
        --seed "$seed" --out "$out/$scene"
    cp "$out/$scene/compare.png" "benches/figures/compare-$scene.png"
done

echo
echo "| scene | seconds per run | method | final best, mean +- std | best of the runs | evaluations per run |"
echo "|---|---:|---|---:|---:|---:|"
for scene in spaceship_volume city_whale tree_sketch1; do
    jq -r --arg scene "$scene" '.seconds as $s | .methods[] |
        "| \($scene) | \($s) | \(.method) | \(.final_mean * 1000 | round / 1000) +- \(.final_std * 1000 | round / 1000) | \(.best * 1000 | round / 1000) | \(.evaluations | round) |"' \
        "$out/$scene/summary.json"
done
