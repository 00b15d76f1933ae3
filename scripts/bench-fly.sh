#!/usr/bin/env bash
# Frames per second while flying in `godel explore` (BENCHMARKS.md, "Flying in the page"):
#   scripts/bench-fly.sh SCENE WIDTH HEIGHT [FRAMES]
# Builds godel (the release build, as README's `cargo run --release`), explores SCENE at
# WIDTH × HEIGHT with one ray a pixel (BENCH_SAMPLES=N: N, a square number, in place of the
# scene's `samples` line), and
# runs tests/browser/bench-fly.mjs in headless chromium (software WebGL2): holds W for FRAMES
# animation frames (default 120) and prints the frames/s, the sizes the dynamic resolution
# chose, and the times to the steps at rest and the full frame. Prints the load average
# before; the server it started is stopped and its folder removed. BENCH_HOVER=1 keeps the
# pointer on the picture while flying (the hovered pixel's record and light ray every frame).
# The page traces each frame on the faster of its kernel and the server's CPU (fly.js);
# BENCH_TRACE=page keeps every frame on the kernel (`?trace=page`); BENCH_MOVING=full traces
# every moving frame at WIDTH × HEIGHT, without the dynamic resolution (`?moving=full`): the
# frame rate at that frame size.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -lt 3 ]; then
    echo "usage: scripts/bench-fly.sh SCENE WIDTH HEIGHT [FRAMES]" >&2
    exit 2
fi
if ! [[ ${BENCH_SAMPLES:-1} =~ ^[1-9][0-9]*$ ]]; then
    echo "BENCH_SAMPLES must be a whole number of rays a pixel, not '$BENCH_SAMPLES'" >&2
    exit 2
fi
query=()
case ${BENCH_TRACE:-} in
    "") ;;
    page) query+=(trace=page) ;;
    *) echo "BENCH_TRACE is 'page' or unset, not '$BENCH_TRACE'" >&2; exit 2 ;;
esac
case ${BENCH_MOVING:-} in
    "") ;;
    full) query+=(moving=full) ;;
    *) echo "BENCH_MOVING is 'full' or unset, not '$BENCH_MOVING'" >&2; exit 2 ;;
esac
scene=$(realpath "$1")
frames=${4:-120}
cd "$root"
cargo build --release -p godel -q
# shellcheck source=bench-server.sh
source "$root/scripts/bench-server.sh"
sed -e "s/^width = .*/width = $2/" -e "s/^height = .*/height = $3/" \
    -e "s/^samples = .*/samples = ${BENCH_SAMPLES:-1}/" "$scene" >"$work/bench.toml"
serve explore "$work/bench.toml"
echo "# $(uptime)"
if [ ${#query[@]} -gt 0 ]; then
    url="$url?$(IFS='&'; echo "${query[*]}")"
fi
cd tests/browser
node bench-fly.mjs "$url" "$work" "$frames"
