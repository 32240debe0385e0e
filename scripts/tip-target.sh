#!/usr/bin/env bash
# The tip target at t = 1 on the 30° release (tip error 1e-4) on a finer grid than the default
# study's, around where the chain and rattle meet it: N = 30 … 50 and k = 3e-3 … 3e-2, against
# a reference extrapolated from the chain at N = 1000 and 2000. One thread, so that no run shares a core with another
# (CPU times are per run). Writes study.csv, findings.md and the charts into OUT
# (assets/tip-target unless given); findings.md's "A tip error of 1e-4" table is the answer.
# Usage: scripts/tip-target.sh [OUT=assets/tip-target]
# About 2 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-assets/tip-target}
cargo build --release --locked --quiet
RAYON_NUM_THREADS=1 target/release/rope study --methods chain,rattle \
    --segments 30,35,40,45,50 --dts 3e-2,2e-2,1.5e-2,1e-2,7e-3,5e-3,3e-3 \
    --reference-segments 2000 --out "$out" --yes
grep -A5 "A tip error of 1e-4" "$out/findings.md"
