#!/usr/bin/env bash
# A page that stops reading: `rope run --web --duration inf --realtime --save F` in headless
# Chromium, the browser stopped (SIGSTOP) for STALL seconds (default 600) while rope's
# resident memory is sampled every 30 s, then resumed: the page must answer and move again,
# and the --save file must verify with `rerun rrd verify` and hold every frame the summary
# says was logged. Writes assets/live-soak/stall.csv. Needs what scripts/web-check.py needs,
# and `rerun` (pip install rerun-sdk==0.36.3).
set -euo pipefail
cd "$(dirname "$0")/.."
stall=${1:-600}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 scripts/web-check.py --seconds 120 \
    --run-args "--duration inf --realtime --save $tmp/stall.rrd --summary $tmp/stall.json" \
    --stall "$stall" --sample-every 30 --soak-csv assets/live-soak/stall.csv \
    --screenshot "$tmp/stall.png"
rerun rrd verify "$tmp/stall.rrd"
rows=$(rerun rrd print "$tmp/stall.rrd" 2> /dev/null | awk '/ - \/rope\/segments - .*LineStrips2D:strips/ { sum += $3 } END { print sum }')
frames=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['frames_logged'])" "$tmp/stall.json")
echo "live-stall: the summary says $frames frames logged; the file holds $rows rows of rope/segments"
[ "$rows" = "$frames" ] || { echo "live-stall: FAILED: the file does not hold every frame"; exit 1; }
echo "live-stall: 1 passed, 0 failed"
