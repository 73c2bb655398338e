#!/usr/bin/env bash
# What watching a run costs it: the same run (scene, seed, generation budget) without a
# viewer, and with the viewer's page open in headless Chromium following it the whole
# time, alternately, REPEATS times each. Prints each run's evaluations per second
# (evaluations / elapsed_s of its summary.json), its best fitness, which must be the same
# in both, and for watched runs the CPU time the browser took meanwhile.
#
# The watched run writes into a folder that `shapegen view` serves and that the browser
# already shows (waiting for the run's first files): a browser already open on the page,
# as a user would have it, so that the browser's own start is not counted. The browser
# runs in real time (kept open by --remote-debugging-port), polling as a user's would.
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
# The processes below process $1, its children's children too.
descendants() {
  local pid
  for pid in $(ps -o pid= --ppid "$1"); do
    echo "$pid"
    descendants "$pid"
  done
}
# CPU time (user and system, its reaped children's included, in 1/100 s) of process $1
# and every process below it.
browser_ticks() {
  local total=0 pid
  for pid in "$1" $(descendants "$1"); do
    if [ -r "/proc/$pid/stat" ]; then
      total=$((total + $(awk '{print $14 + $15 + $16 + $17}' "/proc/$pid/stat")))
    fi
  done
  echo "$total"
}
run_args=(run "$scene" --cpu --seed 1 --generations "$generations" --force)

for r in $(seq 1 "$repeats"); do
  "$bin" "${run_args[@]}" --out "$work/plain" >/dev/null 2>&1
  report plain "$work/plain"

  rm -rf "$work/viewed" "$work/profile" "$work/view.log"
  mkdir -p "$work/viewed"
  "$bin" view "$work/viewed" 2>"$work/view.log" &
  view_pid=$!
  pids+=("$view_pid")
  until url="$(grep -so 'http://[0-9.:]*/' "$work/view.log")"; do sleep 0.05; done
  "$chromium" --headless --no-sandbox --disable-gpu --disable-background-networking \
    --disable-component-update --disable-sync --no-first-run \
    --user-data-dir="$work/profile" --remote-debugging-port=0 "$url" >/dev/null 2>&1 &
  browser_pid=$!
  pids+=("$browser_pid")
  sleep 3
  before="$(browser_ticks "$browser_pid")"
  "$bin" "${run_args[@]}" --out "$work/viewed" >/dev/null 2>&1
  after="$(browser_ticks "$browser_pid")"
  report viewed "$work/viewed"
  echo "        the browser took $(awk -v t=$((after - before)) 'BEGIN { printf "%.2f", t / 100 }') s of CPU meanwhile"
  kill "$browser_pid" "$view_pid" 2>/dev/null || true
  wait "$browser_pid" "$view_pid" 2>/dev/null || true
done
