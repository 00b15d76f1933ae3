#!/usr/bin/env bash
# Frames per second while flying in `godel explore` (BENCHMARKS.md, "Flying in the page"):
#   scripts/bench-fly.sh SCENE WIDTH HEIGHT [FRAMES]
# Builds godel (the dev profile, optimized), explores SCENE at WIDTH × HEIGHT with one ray a
# pixel, and runs tests/browser/bench-fly.mjs in headless chromium (software WebGL2): holds W
# for FRAMES animation frames (default 120) and prints the frames/s, the sizes the dynamic
# resolution chose, and the time to the full frame once at rest. Prints the load average
# before; the server it started is stopped and its folder removed.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -lt 3 ]; then
    echo "usage: scripts/bench-fly.sh SCENE WIDTH HEIGHT [FRAMES]" >&2
    exit 2
fi
scene=$(realpath "$1")
frames=${4:-120}
cd "$root"
cargo build -p godel -q
work=$(mktemp -d)
server=""
trap '[ -n "$server" ] && kill "$server" 2>/dev/null; wait 2>/dev/null; rm -rf "$work"' EXIT
sed -e "s/^width = .*/width = $2/" -e "s/^height = .*/height = $3/" \
    -e "s/^samples = .*/samples = 1/" "$scene" >"$work/bench.toml"
"$root/target/debug/godel" explore "$work/bench.toml" --port 0 >"$work/server.log" 2>"$work/server.err" &
server=$!
url=""
for _ in $(seq 1 3000); do
    url=$(sed -n 's/^godel explore: serving \(http:[^ ]*\)$/\1/p' "$work/server.log")
    [ -n "$url" ] && break
    kill -0 "$server" 2>/dev/null || break
    sleep 0.1
done
[ -n "$url" ] || { echo "the server did not start:" >&2; cat "$work/server.err" >&2; exit 1; }
echo "# $(uptime)"
cd tests/browser
node bench-fly.mjs "$url" "$work" "$frames"
