#!/usr/bin/env bash
# Makes the README's picture of a flight, docs/flight.png (README "Exploring"):
#   scripts/flight-picture.sh [OUT.png] [SPEED] [UNTIL]
# Builds godel, explores the reference scene (scenes/reference.toml) and runs tests/browser/flight-picture.mjs
# in headless chromium (software WebGL2): falls freely toward the earth at SPEED (default 0.6
# c) until the observer's time passes UNTIL (default 0.9), waits for the full frame traced in
# the browser (about 40 s on 2 cores), hovers a looping image and saves the page to OUT.png
# (default docs/flight.png; written only once the picture is made). The server it started is
# stopped and its folder removed.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(realpath -m "${1:-$root/docs/flight.png}")
speed=${2:-0.6}
until=${3:-0.9}
cd "$root"
cargo build -p godel -q
work=$(mktemp -d)
server=""
trap '[ -n "$server" ] && kill "$server" 2>/dev/null; wait 2>/dev/null; rm -rf "$work"' EXIT
"$root/target/debug/godel" explore "$root/scenes/reference.toml" --port 0 >"$work/server.log" 2>"$work/server.err" &
server=$!
url=""
for _ in $(seq 1 3000); do
    url=$(sed -n 's/^godel explore: serving \(http:[^ ]*\)$/\1/p' "$work/server.log")
    [ -n "$url" ] && break
    kill -0 "$server" 2>/dev/null || break
    sleep 0.1
done
[ -n "$url" ] || { echo "the server did not start:" >&2; cat "$work/server.err" >&2; exit 1; }
cd tests/browser
node flight-picture.mjs "$url" "$work" "$work/flight.png" "$speed" "$until"
mv "$work/flight.png" "$out"
echo "wrote $out"
