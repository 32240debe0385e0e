#!/usr/bin/env bash
# The time step at fixed N: the worst tip error to t = 3 of each rods method (chain, rattle,
# midpoint) at 0.2, 0.5, 1 and 2 × its stability limit, over that at its default step, from
# the releases at 0°, 30° and 60° and modes 1 and 2, N = 16 … 100 (against the chain
# extrapolated from N = 200, 400, 800). What each method's `tolerance_step_fraction` in its
# descriptor rests on. Writes a Markdown table to stdout. About 3 minutes on 2 cores.
# (The seed scheme is left out: a step past its limit blows it up, its tolerance keeps its default.)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo run --release --locked --quiet --example tolerance_step
