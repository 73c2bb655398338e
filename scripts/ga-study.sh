#!/usr/bin/env bash
# The GA study that preceded the paper (Haubenwallner, CESCG 2017), reproduced with
# `shapegen sweep` on the paper's spaceship scene: one setting at a time around the
# paper's settings for that scene (population 150, elitism 30, initial length 50,
# mutation 30 % split 45 / 45 / 10, parents by 10-tournament and roulette, the original's
# operators), every run with the same evaluation budget; and population again at a fixed
# number of generations, as the CESCG study ran it. docs/ga-study.md shows and reads the
# results.
#
# Usage: scripts/ga-study.sh [OUT_DIR]      (default target/ga-study)
# Environment: RUNS (runs per setting, default 20), EVALUATIONS (budget per run, default
# 20000), SEED (base seed, default 1), JOBS (runs at once, default: one per core).
#
# Writes each sweep to OUT_DIR/KEY, copies its plot
# to docs/ga-study-KEY.png, and prints each sweep's summary and how long it took. A
# sweep already done in OUT_DIR is not run again.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

out="${1:-target/ga-study}"
runs="${RUNS:-20}"
evaluations="${EVALUATIONS:-20000}"
seed="${SEED:-1}"
jobs=()
[[ -n "${JOBS:-}" ]] && jobs=(--jobs "$JOBS")
scene=scenes/paper/spaceship_volume.toml

cargo build --release --quiet
mkdir -p "$out" docs

# One sweep per setting: the name of its folder and plot, the swept key, its values, and
# the budget of each run. The last sweeps population at a fixed number of generations
# (50, the CESCG study's), where a larger population also has more evaluations.
sweeps=(
    "population optimizer.population 50,100,150,200,300 --evaluations $evaluations"
    "mutation optimizer.mutation_probability 0.1,0.3,0.5,0.7,0.9 --evaluations $evaluations"
    "elitism optimizer.elitism 0,10,30,60,100 --evaluations $evaluations"
    "initial-length optimizer.initial_length 5,10,20,50,80 --evaluations $evaluations"
    "selection optimizer.selection tournament_roulette,tournament,roulette,random --evaluations $evaluations"
    "population-50-generations optimizer.population 50,100,150,200,300 --generations 50"
)
start=$SECONDS
for sweep in "${sweeps[@]}"; do
    read -r name key values budget_flag budget <<<"$sweep"
    echo "== $name: $key = $values, $runs runs of $budget ${budget_flag#--} each" >&2
    t=$SECONDS
    ./target/release/shapegen sweep "$scene" --method ga --cpu --grid "$key=$values" --runs "$runs" \
        "$budget_flag" "$budget" --seed "$seed" "${jobs[@]}" --out "$out/$name"
    echo "   $name took $((SECONDS - t)) s" >&2
    cp "$out/$name/final-$key.png" "docs/ga-study-$name.png"
done
cp "$out/selection/curves.png" docs/ga-study-selection-curves.png
echo "== all sweeps took $((SECONDS - start)) s" >&2
for sweep in "${sweeps[@]}"; do
    read -r name _ <<<"$sweep"
    echo
    sed -n '/^| /p' "$out/$name/summary.md"
done
