#!/usr/bin/env bash
# Fuzzing: runs every target of fuzz/ (cargo fuzz, libFuzzer) for SECONDS each, from a
# corpus seeded with the project's own files (scenes, genomes, meshes, targets) and
# fuzz/seeds/, and prints each target's count of inputs tried. A crash, an abort, a
# leak of the memory limit or a timeout stops the script with libFuzzer's report, the
# input under fuzz/artifacts/TARGET/.
#
# Usage: scripts/fuzz.sh SECONDS [TARGET ...]     (default: every target)
# Environment: FUZZ_TOOLCHAIN (default: cargo's own), FUZZ_SANITIZER (default none),
#   FUZZ_RSS_MB (libFuzzer's -rss_limit_mb, default 2048),
#   FUZZ_MALLOC_MB (-malloc_limit_mb: the largest single allocation, default 512),
#   FUZZ_LOG (a folder for each target's log, default fuzz/logs).
# Needs cargo-fuzz (`cargo install cargo-fuzz`) and a C++ compiler.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
seconds="${1:?usage: scripts/fuzz.sh SECONDS [TARGET ...]}"
shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene_toml lot_geojson genome_json checkpoint obj_mesh stl_mesh ply_mesh gltf_mesh point_cloud target_image request_path)
rss="${FUZZ_RSS_MB:-2048}"
malloc="${FUZZ_MALLOC_MB:-512}"
logs="${FUZZ_LOG:-$root/fuzz/logs}"

# cargo fuzz runs on the stable toolchain without a sanitizer: the project has no unsafe
# code, and what is looked for is a panic, an abort, a timeout or an allocation beyond
# the limits. FUZZ_TOOLCHAIN=nightly FUZZ_SANITIZER=address adds AddressSanitizer.
cargo=(cargo)
[ -z "${FUZZ_TOOLCHAIN:-}" ] || cargo+=("+$FUZZ_TOOLCHAIN")
sanitizer="${FUZZ_SANITIZER:-none}"

# seed TARGET FILES..: copies the files into the target's corpus, named by content.
seed() {
    local dir="fuzz/corpus/$1"
    shift
    mkdir -p "$dir"
    for file in "$@"; do
        [ -f "$file" ] || continue
        cp "$file" "$dir/$(sha1sum "$file" | cut -c1-40)"
    done
}
shopt -s nullglob
seed lot_geojson scenes/lots/*.geojson fuzz/seeds/lot_geojson/*
seed scene_toml scenes/*.toml scenes/paper/*.toml examples/*/*.toml fuzz/seeds/scene_toml/*
seed genome_json scenes/targets/*.genome.json examples/*/targets/*.genome.json fuzz/seeds/genome_json/*
seed checkpoint fuzz/seeds/checkpoint/*
seed obj_mesh generators/meshes/*.obj scenes/targets/*.obj scenes/paper/*/*.obj fuzz/seeds/obj_mesh/*
seed stl_mesh fuzz/seeds/stl_mesh/*
seed ply_mesh fuzz/seeds/ply_mesh/*
seed gltf_mesh fuzz/seeds/gltf_mesh/*
seed point_cloud fuzz/seeds/point_cloud/*
seed target_image scenes/targets/*.png scenes/paper/*/*.png fuzz/seeds/target_image/*
seed request_path fuzz/seeds/request_path/*
# The original's derivations (JSON of another shape, gzip-compressed in the repository).
golden="$(mktemp -d)"
trap 'rm -rf "$golden"' EXIT
for file in generators/tests/golden/*.json.gz; do
    gzip -dc "$file" >"$golden/$(basename "$file" .gz)"
done
seed genome_json "$golden"/*.json

cd fuzz
mkdir -p "$logs"
for target in "${targets[@]}"; do
    log="$logs/$target.log"
    echo "== $target: $seconds s (${cargo[*]} fuzz run --sanitizer $sanitizer $target -- -max_total_time=$seconds -rss_limit_mb=$rss -malloc_limit_mb=$malloc)"
    if ! "${cargo[@]}" fuzz run --sanitizer "$sanitizer" "$target" -- \
        -max_total_time="$seconds" -rss_limit_mb="$rss" -malloc_limit_mb="$malloc" \
        -timeout=60 -print_final_stats=1 >"$log" 2>&1; then
        tail -n 60 "$log"
        echo "$target: FAILED (log: $log, input: fuzz/artifacts/$target/)"
        exit 1
    fi
    runs="$(awk '/stat::number_of_executed_units/ { print $2 }' "$log")"
    rss_peak="$(awk '/stat::peak_rss_mb/ { print $2 }' "$log")"
    echo "$target: $runs inputs in $seconds s, no crash; peak RSS $rss_peak MB"
done
