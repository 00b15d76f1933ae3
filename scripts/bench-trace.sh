#!/usr/bin/env bash
# The page's GPU tracer against the CPU exact tracer (BENCHMARKS.md, "The page's GPU tracer"):
#   scripts/bench-trace.sh SCENE WIDTH HEIGHT [RUNS]
# Builds godel (release), renders SCENE at WIDTH × HEIGHT with one ray a pixel by the exact
# tracer on all cores (its summary line gives its rays/s), serves the data file with
# `godel view --port 0` and runs tests/browser/bench-trace.mjs against it: RUNS traces of the
# same scene in headless chromium's WebGL2 (default 2; the first one also compiles the
# kernel). Prints the load average before each part; the server it started is stopped.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -lt 3 ]; then
    echo "usage: scripts/bench-trace.sh SCENE WIDTH HEIGHT [RUNS]" >&2
    exit 2
fi
scene=$(realpath "$1")
width=$2
height=$3
runs=${4:-2}
cd "$root"
cargo build --release -p godel -q
godel="$root/target/release/godel"
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

echo "# cpu: $(uptime)"
"$godel" render "$scene" --method exact --samples 1 --width "$width" --height "$height" \
    --name bench -o "$work"
: >"$work/server.log"
"$godel" view "$work/bench.exr" --port 0 >"$work/server.log" 2>"$work/server.err" &
server=$!
url=""
# Waits (bounded: one minute) for the line with the server's address.
for _ in $(seq 1 600); do
    url=$(sed -n 's/^godel view: serving \(http:[^ ]*\)$/\1/p' "$work/server.log")
    [ -n "$url" ] && break
    kill -0 "$server" 2>/dev/null || break
    sleep 0.1
done
if [ -z "$url" ]; then
    echo "the server did not start:" >&2
    cat "$work/server.err" >&2
    exit 1
fi
echo "# page: $(uptime)"
cd tests/browser
node bench-trace.mjs "$url" "$work" "$runs"
