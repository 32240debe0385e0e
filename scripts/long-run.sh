#!/usr/bin/env bash
# Long runs: does the energy stay bounded? `rattle` from 0°, 30°, 60° and 90° for T time units
# (10 000 unless given); `midpoint` from 0°, 30° and 60° for T; then the four methods from 30°
# for T/10 (the RK4 chain takes substeps through the chaotic swing and would need over an hour
# for 10 000), each at N = 100 and its default step; then `rattle` from 0° and 30° for T/10 at
# its default step, a half and a quarter of it (what a finer step buys). Writes long_run.md
# (the table), long_run.csv and long_run.svg/.png into OUT/rattle, OUT/midpoint, OUT/methods
# and OUT/steps (OUT = assets/long-run unless given). PARTS picks some of the four parts
# (default: all): e.g. PARTS="midpoint methods" scripts/long-run.sh.
# Usage: [PARTS="rattle midpoint methods steps"] scripts/long-run.sh [T=10000] [OUT=assets/long-run]
# About an hour on two cores at T = 10 000.
set -euo pipefail
duration=${1:-10000}
cd "$(dirname "$0")/.."
out=${2:-assets/long-run}
parts=${PARTS:-rattle midpoint methods steps}
cargo build --release --locked --quiet
for part in $parts; do
    case $part in
    rattle) target/release/rope study --long-run "$duration" --methods rattle --angle 0,30,60,90 \
        --out "$out/rattle" --yes ;;
    midpoint) target/release/rope study --long-run "$duration" --methods midpoint --angle 0,30,60 \
        --out "$out/midpoint" --yes ;;
    methods) target/release/rope study --long-run "$((duration / 10))" \
        --methods seed,chain,rattle,midpoint --angle 30 --out "$out/methods" --yes ;;
    steps) target/release/rope study --long-run "$((duration / 10))" --methods rattle --angle 0,30 \
        --dts 5e-4,2.5e-4,1.25e-4 --out "$out/steps" --yes ;;
    *) echo "long-run: unknown part '$part' (rattle, midpoint, methods or steps)" >&2; exit 2 ;;
    esac
done
echo "long-run: tables in $out/{$(echo $parts | tr ' ' ,)}/long_run.md"
