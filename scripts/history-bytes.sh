#!/usr/bin/env bash
# The history a served run sends per time unit, as a viewer receives it. `rope run
# --serve-grpc` runs RUN_ARGS as fast as it can for UNITS time units, then for 2 × UNITS; each
# time a late `rerun URL --save` takes the whole history from its endpoint (the live
# picture's endpoint is left out) and `rerun rrd stats` counts its data (uncompressed Arrow
# IPC). The difference over the UNITS between them is what a page left open pays a time
# unit, past the start (where the history sends sooner) and without what is sent once.
#
#   scripts/history-bytes.sh UNITS [RUN_ARGS...]
#   scripts/history-bytes.sh 400 --method seed,chain,midpoint --angle 80 --dt 2e-3
#
# Used to show that a soak accelerated by its flags sends what the run it stands for sends
# (docs/measurements.md, "A page left open"). Needs `pip install rerun-sdk==0.36.3`.
set -euo pipefail
cd "$(dirname "$0")/.."
units=${1:?usage: $0 UNITS [RUN_ARGS...]}
shift
port=${HISTORY_BYTES_PORT:-9971}
out=$(mktemp -d)
rope=
trap 'kill $rope 2> /dev/null || true; rm -rf "$out"' EXIT

# The data bytes of the history of a run of $1 time units, on standard output.
history_bytes() {
    target/release/rope run --serve-grpc "127.0.0.1:$port" --duration "$1" --realtime 1000 "${@:2}" \
        2> "$out/rope.txt" &
    rope=$!
    # A finite served run keeps serving once it ends: wait for its summary, then join late.
    until grep -q " steps to t = " "$out/rope.txt" 2> /dev/null; do
        kill -0 $rope 2> /dev/null || { cat "$out/rope.txt" >&2; exit 1; }
        sleep 1
    done
    sleep 2
    timeout 10 rerun "rerun+http://127.0.0.1:$port/proxy" --save "$out/history.rrd" > /dev/null 2>&1 || true
    kill $rope
    wait $rope 2> /dev/null || true
    grep -o "a browser page can stay open.*the live picture" "$out/rope.txt" >&2 || true
    grep " steps to t = " "$out/rope.txt" | cut -c1-110 >&2
    rerun rrd stats "$out/history.rrd" 2> /dev/null |
        awk '/^Size \(data only, uncompressed\)/ { data = 1 }
             data && /^ipc_size_bytes_total/ {
                 scale = $4 == "B" ? 1 : $4 == "KiB" ? 1024 : $4 == "MiB" ? 1048576 : 1073741824
                 print $3 * scale; exit }'
}

# Not in $(…): a subshell's rope would be out of the trap's reach.
history_bytes "$units" "$@" > "$out/short"
history_bytes "$((2 * units))" "$@" > "$out/long"
short=$(cat "$out/short")
long=$(cat "$out/long")
awk -v s="$short" -v l="$long" -v u="$units" 'BEGIN {
    printf "history data: %.0f bytes over %d time units, %.0f over %d: %.2f kB a time unit\n",
        s, u, l, 2 * u, (l - s) / u / 1000 }'
