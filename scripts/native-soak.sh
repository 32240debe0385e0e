#!/usr/bin/env bash
# The native viewer on a served run left running: `rope run --duration inf --realtime
# --serve-grpc` and a headless `rerun` 0.36.3 joined to its endpoints, the viewer's resident
# memory sampled every 60 s for SECONDS (default 3600).
#
#   scripts/native-soak.sh [SECONDS] [both|history|live] [PORT]
#
# JOIN says which endpoints the viewer joins: both (what a user is told to do), the
# history's alone, or the live picture's alone (to tell which one the viewer's memory grows
# with). PORT is the history's endpoint (default 9981; the live picture's is PORT + 1; the
# viewer's own server takes PORT + 9). Writes assets/live-soak/native-JOIN.csv (where the
# memory goes: scripts/native-growth.py). Needs
# `pip install rerun-sdk==0.36.3` and Vulkan (apt-get install mesa-vulkan-drivers libvulkan1).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-3600}
join=${2:-both}
port=${3:-9981}
history="rerun+http://127.0.0.1:$port/proxy"
live="rerun+http://127.0.0.1:$((port + 1))/proxy"
case "$join" in
    both) urls=("$history" "$live") ;;
    history) urls=("$history") ;;
    live) urls=("$live") ;;
    *) echo "usage: $0 [SECONDS] [both|history|live] [PORT]" >&2; exit 2 ;;
esac
csv="assets/live-soak/native-$join.csv"
target/release/rope run --duration inf --realtime --serve-grpc "127.0.0.1:$port" 2> "/tmp/native-soak-rope-$join.txt" &
rope=$!
sleep 3
rerun --headless --port $((port + 9)) "${urls[@]}" > "/tmp/native-soak-viewer-$join.txt" 2>&1 &
launcher=$!
trap 'kill $launcher $rope 2> /dev/null || true; pkill -f "rerun --headless --port $((port + 9))" || true' EXIT
sleep 5
viewer=$(pgrep -f "rerun_cli/rerun --headless --port $((port + 9))" | head -1)  # the viewer itself, below pip's launcher
rss() { awk '/VmRSS/ { print $2 / 1000 }' "/proc/$1/status"; }
echo "seconds,viewer_mb,rope_mb" > "$csv"
start=$(date +%s)
while (( $(date +%s) - start < seconds )); do
    sleep 60
    line="$(( $(date +%s) - start )),$(rss "$viewer"),$(rss $rope)"
    echo "$line" >> "$csv"
    echo "native-soak: $join $line"
done
