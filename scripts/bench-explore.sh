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
work=$(mktemp -d)
server=""
stop() {
    if [ -n "$server" ]; then
        kill "$server" 2>/dev/null || true
        wait "$server" 2>/dev/null || true
        server=""
    fi
}
trap 'stop; rm -rf "$work"' EXIT

# Starts the server, waits (bounded: 10 minutes) for the line with its address, sets $url.
start() {
    : >"$work/server.log"
    "$root/target/release/godel" explore "$scene" --threads "$threads" --port 0 \
        >"$work/server.log" 2>"$work/server.err" &
    server=$!
    url=""
    for _ in $(seq 1 6000); do
        url=$(sed -n 's/^godel explore: serving \(http:[^ ]*\)$/\1/p' "$work/server.log")
        [ -n "$url" ] && return 0
        kill -0 "$server" 2>/dev/null || break
        sleep 0.1
    done
    echo "the server did not start:" >&2
    cat "$work/server.err" >&2
    exit 1
}

cd tests/browser
for mode in ${BENCH_MODES:-event play}; do
    start
    echo "# $mode: $(uptime)"
    if [ "$mode" = event ]; then
        node bench-explore.mjs "$url" "$work" event "$events"
    else
        node bench-explore.mjs "$url" "$work" play "$seconds" $rate
    fi
    stop
done
