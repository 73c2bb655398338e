#!/usr/bin/env bash
# What watching a run costs it: the same run (scene, seed, generation budget) without a
# viewer, and with `--view` and the viewer's page open in headless Chromium following it
# the whole time, alternately, REPEATS times each. Prints each run's evaluations per
# second (evaluations / elapsed_s of its summary.json) and its best fitness, which must
# be the same in both.
#
# Usage: scripts/view-overhead.sh [GENERATIONS] [REPEATS]
# Environment: SHAPEGEN (default target/release/shapegen; build it with
#   `cargo build --release`), CHROMIUM (default chromium), SCENE (default
#   scenes/city_skyline.toml).
set -euo pipefail
cd "$(dirname "$0")/.."
generations="${1:-3000}"
repeats="${2:-3}"
bin="${SHAPEGEN:-target/release/shapegen}"
chromium="${CHROMIUM:-chromium}"
scene="${SCENE:-scenes/city_skyline.toml}"
work="$(mktemp -d)"
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT

field() { grep -o "\"$1\": [0-9.e+-]*" "$2" | head -1 | sed 's/.*: //'; }
report() {
  local label="$1" dir="$2"
  local evaluations elapsed best
  evaluations="$(field evaluations "$dir/summary.json")"
  elapsed="$(field elapsed_s "$dir/summary.json")"
  best="$(field best_fitness "$dir/summary.json")"
  awk -v l="$label" -v e="$evaluations" -v t="$elapsed" -v b="$best" \
    'BEGIN { printf "%-7s %8d evaluations in %7.3f s: %9.0f evaluations/s, best %s\n", l, e, t, e / t, b }'
}
run_args=(run "$scene" --cpu --seed 1 --generations "$generations" --force)

for r in $(seq 1 "$repeats"); do
  "$bin" "${run_args[@]}" --out "$work/plain" >/dev/null 2>&1
  report plain "$work/plain"

  rm -rf "$work/viewed" "$work/profile"
  "$bin" "${run_args[@]}" --view --out "$work/viewed" >/dev/null 2>"$work/run.log" &
  run_pid=$!
  pids+=("$run_pid")
  until url="$(grep -o 'http://[0-9.:]*/' "$work/run.log")"; do sleep 0.05; done
  # The page follows the run until it ends: a request per save, the model reloaded and
  # redrawn (on the CPU, SwiftShader) at each new best, the curve at each save.
  "$chromium" --headless --no-sandbox --disable-gpu --disable-background-networking \
    --disable-component-update --disable-sync --no-first-run \
    --user-data-dir="$work/profile" --virtual-time-budget=3600000 --dump-dom "$url" \
    >/dev/null 2>&1 &
  browser_pid=$!
  pids+=("$browser_pid")
  until [ -f "$work/viewed/summary.json" ]; do sleep 0.05; done
  kill -INT "$run_pid"
  wait "$run_pid" || true
  kill "$browser_pid" 2>/dev/null || true
  wait "$browser_pid" 2>/dev/null || true
  report viewed "$work/viewed"
done
