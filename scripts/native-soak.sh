#!/usr/bin/env bash
# The native viewer on a served run left running: `rope run --duration inf --realtime
# --serve-grpc` and a headless `rerun` 0.36.3 joined to its two endpoints (the history and
# the live picture), the viewer's resident memory sampled every 60 s for SECONDS (default
# 3600). Writes assets/live-soak/native.csv. Needs `pip install rerun-sdk==0.36.3` and
# Vulkan (apt-get install mesa-vulkan-drivers libvulkan1).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-3600}
port=9981
csv=assets/live-soak/native.csv
target/release/rope run --duration inf --realtime --serve-grpc "127.0.0.1:$port" 2> /tmp/native-soak-rope.txt &
rope=$!
sleep 3
rerun --headless --port 9990 "rerun+http://127.0.0.1:$port/proxy" "rerun+http://127.0.0.1:$((port + 1))/proxy" > /tmp/native-soak-viewer.txt 2>&1 &
launcher=$!
trap 'kill $launcher $rope 2> /dev/null || true; pkill -f "rerun --headless --port 9990" || true' EXIT
sleep 5
viewer=$(pgrep -f "rerun_cli/rerun --headless" | head -1)  # the viewer itself, below pip's launcher
rss() { awk '/VmRSS/ { print $2 / 1000 }' "/proc/$1/status"; }
echo "seconds,viewer_mb,rope_mb" > "$csv"
start=$(date +%s)
while (( $(date +%s) - start < seconds )); do
    sleep 60
    line="$(( $(date +%s) - start )),$(rss $viewer),$(rss $rope)"
    echo "$line" >> "$csv"
    echo "native-soak: $line"
done
