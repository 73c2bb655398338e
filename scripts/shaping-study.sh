#!/usr/bin/env bash
# Distance shaping against the published fitness, on targets the generators cannot reach
# exactly: each scene is run plain and shaped with the same seeds and the same wall time,
# and every best is scored in the plain scene, so that both are judged by the published
# fitness.
#
# Usage: scripts/shaping-study.sh [OUT_DIR]      (default target/shaping-study)
# Environment: RUNS (seeds 1..RUNS, default 5), SECONDS_PER_RUN (default 60),
#   METHOD (default hybrid), THREADS (default 2).
#
# Prints, per scene and seed, the published fitness of the plain run's best and of the
# shaped run's best, and the medians.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
out="${1:-target/shaping-study}"
runs="${RUNS:-5}"
seconds="${SECONDS_PER_RUN:-60}"
method="${METHOD:-hybrid}"
threads="${THREADS:-2}"
cargo build --release --quiet --bin shapegen
mkdir -p "$out"
bin=target/release/shapegen
pairs=(
    "tree_sketch_offset tree_sketch_offset_shaped"
    "paper/spaceship_volume spaceship_volume_shaped"
)
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
published() { "$bin" score "scenes/$1.toml" --cpu --genomes "$2" 2>/dev/null | sed 's/.*"fitness":\([^,]*\),.*/\1/'; }
for pair in "${pairs[@]}"; do
    read -r plain shaped <<<"$pair"
    printf '%s (plain) against %s, %s, %s s\n' "$plain" "$shaped" "$method" "$seconds"
    printf 'seed\tplain\tshaped\n'
    plains=()
    shapeds=()
    for seed in $(seq 1 "$runs"); do
        for scene in "$plain" "$shaped"; do
            "$bin" --threads "$threads" run "scenes/$scene.toml" --cpu --method "$method" \
                --seconds "$seconds" --generations 1000000000 --seed "$seed" --force --out "$out/${scene//\//_}-$seed" >/dev/null 2>&1
        done
        p="$(published "$plain" "$out/${plain//\//_}-$seed/best.genome.json")"
        s="$(published "$plain" "$out/${shaped//\//_}-$seed/best.genome.json")"
        plains+=("$p")
        shapeds+=("$s")
        printf '%s\t%s\t%s\n' "$seed" "$p" "$s"
    done
    printf 'median\t%s\t%s\n\n' "$(printf '%s\n' "${plains[@]}" | median)" "$(printf '%s\n' "${shapeds[@]}" | median)"
done
