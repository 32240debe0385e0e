#!/usr/bin/env bash
# Long runs: does the energy stay bounded? `rattle` from 0°, 30°, 60° and 90° for T time units
# (10 000 unless given), then the three methods from 30° for T/10 (the RK4 chain takes
# substeps through the chaotic swing and would need over an hour for 10 000), each at N = 100
# and its default step; then `rattle` from 0° and 30° for T/10 at its default step, a half and
# a quarter of it (what a finer step buys). Writes long_run.md (the table), long_run.csv and
# long_run.svg/.png into OUT/rattle, OUT/methods and OUT/steps (OUT = assets/long-run unless
# given).
# Usage: scripts/long-run.sh [T=10000] [OUT=assets/long-run]
# About 40 minutes on two cores at T = 10 000.
set -euo pipefail
duration=${1:-10000}
cd "$(dirname "$0")/.."
out=${2:-assets/long-run}
cargo build --release --locked --quiet
target/release/rope study --long-run "$duration" --methods rattle --angle 0,30,60,90 \
    --out "$out/rattle" --yes
target/release/rope study --long-run "$((duration / 10))" --methods seed,chain,rattle --angle 30 \
    --out "$out/methods" --yes
target/release/rope study --long-run "$((duration / 10))" --methods rattle --angle 0,30 \
    --dts 5e-4,2.5e-4,1.25e-4 --out "$out/steps" --yes
echo "long-run: tables in $out/{rattle,methods,steps}/long_run.md"
