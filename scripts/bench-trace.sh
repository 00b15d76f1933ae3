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
# shellcheck source=bench-server.sh
source "$root/scripts/bench-server.sh"

echo "# cpu: $(uptime)"
"$root/target/release/godel" render "$scene" --method exact --samples 1 \
    --width "$width" --height "$height" --name bench -o "$work"
serve view "$work/bench.exr"
echo "# page: $(uptime)"
cd tests/browser
node bench-trace.mjs "$url" "$work" "$runs"
