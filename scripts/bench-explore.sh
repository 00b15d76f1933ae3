#!/usr/bin/env bash
# Benchmarks of `godel explore` (BENCHMARKS.md, "Explore (issue 15)"):
#   scripts/bench-explore.sh [SCENE] [THREADS] [N_EVENTS] [PLAY_SECONDS] [RATE]
# (defaults: scenes/reference.toml 2 10 10, the page's own play rate; an empty SCENE is the
# default). Builds godel (release),
# then twice starts `godel explore SCENE --threads THREADS --port 0` and runs
# tests/browser/bench-explore.mjs against it: `event` (time from a POST of a new event to its
# coarse and its full frame, N_EVENTS events, plain fetch) and `play` (frames per second the
# page shows while playing time, headless chromium). Prints the two JSON results and the load
# average before each; the servers it started are stopped at the end. BENCH_MODES="play" (or
# "event") runs only that mode.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
scene=$(realpath "${1:-$root/scenes/reference.toml}")
threads=${2:-2}
events=${3:-10}
seconds=${4:-10}
rate=${5:-}
cd "$root"
cargo build --release -p godel -q
# shellcheck source=bench-server.sh
source "$root/scripts/bench-server.sh"

cd tests/browser
for mode in ${BENCH_MODES:-event play}; do
    serve explore "$scene" --threads "$threads"
    echo "# $mode: $(uptime)"
    if [ "$mode" = event ]; then
        node bench-explore.mjs "$url" "$work" event "$events"
    else
        node bench-explore.mjs "$url" "$work" play "$seconds" $rate
    fi
    stop
done
