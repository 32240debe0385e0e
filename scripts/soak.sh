#!/usr/bin/env bash
# Soak: an endless, realtime run at N = 100 in serve mode, its resident memory sampled every
# 10 s. Usage: scripts/soak.sh [SECONDS=600] [SERVER_MEMORY_LIMIT=512MB] [OUT=soak.csv]
# Prints the samples as they come and writes them to OUT (seconds,rss_mb; MB = 10^6 bytes, as
# in the limit) and the run's own messages beside it (OUT with .log for .csv).
set -euo pipefail
seconds=${1:-600}
limit=${2:-512MB}
out=$(realpath "${3:-soak.csv}")
log=${out%.csv}.log
cd "$(dirname "$0")/.."
cargo build --release --locked --quiet
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
target/release/rope run --duration inf --realtime --segments 100 \
    --serve-grpc "127.0.0.1:$port" --server-memory-limit "$limit" 2>"$log" &
pid=$!
trap 'kill -TERM $pid 2>/dev/null || true' EXIT
echo "seconds,rss_mb" | tee "$out"
for ((t = 0; t <= seconds; t += 10)); do
    rss_mb=$(awk '/^VmRSS/ {printf "%.1f", $2 * 1024 / 1e6}' "/proc/$pid/status")
    echo "$t,$rss_mb" | tee -a "$out"
    [ "$t" -lt "$seconds" ] && sleep 10
done
kill -TERM $pid
wait $pid || true
trap - EXIT
echo "soak: $seconds s with --server-memory-limit $limit; samples in $out, the run's messages in $log"
