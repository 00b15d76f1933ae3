#!/usr/bin/env bash
# Makes the picture of a flight, docs/guide/src/pictures/flight.png (README, and the guide's
# docs/guide/src/explore.md):
#   scripts/flight-picture.sh [OUT.png] [SPEED] [UNTIL]
# Builds godel, explores the reference scene (scenes/reference.toml) and runs tests/browser/flight-picture.mjs
# in headless chromium (software WebGL2): falls freely toward the earth at SPEED (default 0.6
# c) until the observer's time passes UNTIL (default 0.9), waits for the full frame traced in
# the browser (`?trace=page`: the picture shows the page's own kernel; about 40 s on 2
# cores), hovers a looping image and saves the page to OUT.png
# (default docs/guide/src/pictures/flight.png; written only once the picture is made). The
# server it started is stopped and its folder removed.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(realpath -m "${1:-$root/docs/guide/src/pictures/flight.png}")
speed=${2:-0.6}
until=${3:-0.9}
cd "$root"
cargo build -p godel -q
godel="$root/target/debug/godel"
# shellcheck source=bench-server.sh
source "$root/scripts/bench-server.sh"
serve explore "$root/scenes/reference.toml"
cd tests/browser
node flight-picture.mjs "$url?trace=page" "$work" "$work/flight.png" "$speed" "$until"
mv "$work/flight.png" "$out"
echo "wrote $out"
