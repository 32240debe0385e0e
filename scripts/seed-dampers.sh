#!/usr/bin/env bash
# Can a damper of the grid-scale sawtooth save the report's scheme from its blow-up while
# keeping its first order and its accuracy at the report's setting? Builds the probe patch
# docs/probes/seed-grid-dampers.patch into a separate binary (target/seed-probe; the working
# tree is restored on exit), then for each damper:
#   - how long the 30° release lives at N = 100 and N = 400 at the default step (to t = 200);
#   - the tip error and energy deviation at t = 1 at N = 25 … 400, k = 1e-5 (the report's k).
# Usage: scripts/seed-dampers.sh [OUT=/tmp/seed-dampers]. About 3 minutes after the build.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-/tmp/seed-dampers}
mkdir -p "$out"
git diff --quiet -- src/methods/seed.rs || { echo "src/methods/seed.rs has changes; commit or stash them first" >&2; exit 1; }
trap 'git checkout -- src/methods/seed.rs' EXIT
git apply docs/probes/seed-grid-dampers.patch
cargo build --release --locked --quiet
cp target/release/rope target/seed-probe
git checkout -- src/methods/seed.rs
trap - EXIT
cargo build --release --locked --quiet
probe=target/seed-probe
dampers=("none" "SEED_PROBE_VISCOSITY=10" "SEED_PROBE_VISCOSITY=50" "SEED_PROBE_FILTER_NEW=0.1"
    "SEED_PROBE_FILTER_BOTH=10" "SEED_PROBE_FILTER_BOTH=50")
echo "| damper | N | lived to t (of 200) | why it stopped |"
echo "|---|---|---|---|"
for d in "${dampers[@]}"; do
    for n in 100 400; do
        env ${d/none/X=0} "$probe" run --method seed --angle 30 --segments "$n" --duration 200 \
            --no-error-estimate --log-rate 10 --save "$out/run.rrd" --summary "$out/run.json" \
            >/dev/null 2>&1 || true
        python3 - "$out/run.json" "$d" "$n" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); d = s["diverged"]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {d['time'] if d else 200:.1f} | {d['reason'][:40] + '…' if d else 'lived'} |")
PY
    done
done
echo
echo "| damper | N | tip error at t = 1 | energy deviation | status |"
echo "|---|---|---|---|---|"
for d in "${dampers[@]}"; do
    env ${d/none/X=0} "$probe" study --methods seed --segments 25,50,100,200,400 --dts 1e-5 \
        --reference-segments 1000 --out "$out/study" --yes >/dev/null 2>&1
    python3 - "$out/study/study.csv" "$d" <<'PY'
import csv, sys
for r in csv.DictReader(open(sys.argv[1])):
    tip = float(r["tip_error"]) if r["tip_error"] else float("nan")
    de = float(r["energy_deviation"]) if r["energy_deviation"] else float("nan")
    print(f"| {sys.argv[2]} | {r['segments']} | {tip:.3e} | {de:.3e} | {r['status']} |")
PY
done
