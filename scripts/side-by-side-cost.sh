#!/usr/bin/env bash
# What methods side by side cost: runs `rope run --method METHODS --duration T` as fast as it
# can (one simulation thread per method), and prints each method's busy CPU seconds (its
# simulation thread's time computing: steps, shadow, frames), their sum (what one thread
# stepping them all would take), the wall time, and how many times faster than realtime the
# run went (T / wall: the room a --realtime run has).
#   scripts/side-by-side-cost.sh [METHODS=seed,chain,rattle] [T=60] [N=100] [MORE FLAGS…]
# (e.g. `scripts/side-by-side-cost.sh seed,chain,rattle 60 100 --no-error-estimate`)
set -euo pipefail
methods=${1:-seed,chain,rattle}
duration=${2:-60}
segments=${3:-100}
more=("${@:4}")
cd "$(dirname "$0")/.."
cargo build --release --locked --quiet
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
start=$(date +%s.%N)
target/release/rope run --method "$methods" --duration "$duration" --segments "$segments" \
    --save "$scratch/x.rrd" --summary "$scratch/s.json" "${more[@]}" 2>/dev/null || true
end=$(date +%s.%N)
python3 - "$scratch/s.json" "$start" "$end" "$duration" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
wall = float(sys.argv[3]) - float(sys.argv[2])
duration = float(sys.argv[4])
total = 0.0
print("| method | reached t | CPU s of its thread |")
print("|---|---|---|")
for m in s["methods"]:
    busy = m["cpu_seconds"]
    total += busy
    print(f"| {m['method']} | {m['steps'] * m['dt']:.1f} ({m['status']}) | {busy:.2f} |")
print(f"\nsum of the threads' CPU (one thread for all): {total:.2f} s; wall with a thread each: {wall:.2f} s "
      f"(whole process); simulated {duration:g} time units: {duration / wall:.1f}× realtime with a thread each, "
      f"{duration / total:.1f}× with one thread for all")
PY
