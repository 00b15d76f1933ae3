# Sourced by the scripts that run a browser against a server (bench-explore.sh, bench-trace.sh,
# bench-fly.sh, flight-picture.sh): a work folder, and one `godel` server at a time (the
# release build, or $godel where the script sets it), stopped and the folder removed on exit.
#   serve COMMAND ARGS…   starts `godel COMMAND ARGS… --port 0`, waits (bounded: 10 minutes)
#                         for the line with its address and sets $url; exits if it fails
#   stop                  stops the server started last
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

serve() {
    : >"$work/server.log"
    "${godel:-$root/target/release/godel}" "$@" --port 0 >"$work/server.log" 2>"$work/server.err" &
    server=$!
    url=""
    for _ in $(seq 1 6000); do
        url=$(sed -n "s/^godel $1: serving \(http:[^ ]*\)\$/\1/p" "$work/server.log")
        [ -n "$url" ] && return 0
        kill -0 "$server" 2>/dev/null || break
        sleep 0.1
    done
    echo "the server did not start:" >&2
    cat "$work/server.err" >&2
    exit 1
}
