#!/usr/bin/env bash
# The release atlas `--tolerance` reads for a release run to t ≤ 3: the worst tip error of the
# rods (the chain at its tolerance step) per release angle (0°, 10°, …, 90°, and the held-out
# 5°, 15°, …, 85°) and N = 16 … 566, against the chain extrapolated from N = 800, 1600, 3200.
# Writes assets/release-atlas/atlas.csv (read at build time: rebuild afterwards) and its chart,
# atlas.png and atlas.svg.
# About 20 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p assets/release-atlas
cargo run --release --locked --quiet --example release_atlas > assets/release-atlas/atlas.csv.new
mv assets/release-atlas/atlas.csv.new assets/release-atlas/atlas.csv
cargo run --release --locked --quiet --example release_atlas_chart
