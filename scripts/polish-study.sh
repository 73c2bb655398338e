#!/usr/bin/env bash
# Polishing (a separable CMA-ES over the best model's continuous parameters,
# `optimizer.polish`) against none, at equal evaluation budgets: each scene is
# run with the same seeds and budgets with polishing off and on, and the final fitness
# and IoU (voxel IoU for volume scenes, the mean over views of the silhouette IoU
# otherwise) of each best are printed with their medians.
#
# Usage: scripts/polish-study.sh [OUT_DIR]      (default target/polish-study)
# Environment: RUNS (seeds 1..RUNS, default 5), BUDGETS (evaluations, default
#   "5000 20000 80000"), POLISH (candidates a generation, default 16), THREADS
#   (default 2), SCENES (default: the reachable volume, silhouette and three-view
#   scenes, and the shaped unreachable sketch), METHOD (default hybrid), SETTINGS
#   (more `--set` overrides, e.g. "optimizer.variant=tempered" for rjmcmc).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
out="${1:-target/polish-study}"
runs="${RUNS:-5}"
budgets="${BUDGETS:-5000 20000 80000}"
polish="${POLISH:-16}"
threads="${THREADS:-2}"
scenes="${SCENES:-spaceship_fill2 tree_sketch2 spaceship_views tree_sketch_offset_shaped}"
method="${METHOD:-hybrid}"
settings=()
for s in ${SETTINGS:-}; do settings+=(--set "$s"); done
cargo build --release --quiet --bin shapegen
mkdir -p "$out"
bin=target/release/shapegen
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
# fitness and IoU of a run's summary.json
measure() {
    local summary="$1/summary.json" fitness iou
    fitness="$(sed -n 's/^  "best_fitness": \([^,]*\),/\1/p' "$summary")"
    iou="$(sed -n 's/.*"voxel_iou": \([^,]*\),*/\1/p' "$summary")"
    if [ -z "$iou" ]; then
        iou="$(sed -n 's/.*"iou": \([^,}]*\).*/\1/p' "$summary" | awk '{ s += $1 } END { print s / NR }')"
    fi
    printf '%s %s' "$fitness" "$iou"
}
printf 'method\tscene\tevaluations\tpolish\tseed\tfitness\tiou\n' >"$out/runs.tsv"
for scene in $scenes; do
    for budget in $budgets; do
        printf '%s, %s, %s evaluations\npolish\tmedian fitness\tmedian IoU\n' "$method" "$scene" "$budget"
        for p in 0 "$polish"; do
            fitness=()
            iou=()
            for seed in $(seq 1 "$runs"); do
                dir="$out/$method-$scene-$budget-$p-$seed"
                "$bin" --threads "$threads" run "scenes/$scene.toml" --cpu --method "$method" "${settings[@]}" \
                    --evaluations "$budget" --generations 1000000000 --seconds 100000 \
                    --seed "$seed" --set "optimizer.polish=$p" --force --out "$dir" >/dev/null 2>&1
                read -r f i <<<"$(measure "$dir")"
                fitness+=("$f")
                iou+=("$i")
                printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$method" "$scene" "$budget" "$p" "$seed" "$f" "$i" >>"$out/runs.tsv"
            done
            printf '%s\t%s\t%s\n' "$p" "$(printf '%s\n' "${fitness[@]}" | median)" "$(printf '%s\n' "${iou[@]}" | median)"
        done
        echo
    done
done
echo "every run: $out/runs.tsv"
