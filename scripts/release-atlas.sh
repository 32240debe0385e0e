#!/usr/bin/env bash
# The release atlas `--tolerance` reads for a release run to t ≤ 3: the worst tip error of the
# rods (the chain at its tolerance step) per release angle (0°, 10°, …, 90°, and the held-out
# 5°, 15°, …, 85°) and N = 16 … 566, against the tolerance check's reference read from
# assets/tolerance-check/references.csv where it can judge 1e-4 (from 10° to 90°), else
# computed as the check computes one (the graded rods from 20° up, else the chain) from
# N = 800, 1600, 3200 (from 1600, 3200, 6400 where the first errs by more than 3e-6), and
# below 20°, where no other rods may be chosen, on to N = 1131, and to 3200 where the
# reference could judge 1e-4 (from 10°).
# Writes assets/release-atlas/atlas.csv (read at build time: rebuild afterwards) and its chart,
# atlas.png and atlas.svg. The committed one took 21 min 22 s of wall on 2 cores, 2 477 s of
# CPU, with ROPE_RUN_CACHE=DIR holding 0°'s reference runs; again with every reference run
# kept, 53 s.
#
# `scripts/release-atlas.sh graded`: the same of the graded rods (`--method graded`) from 20°
# up to N = 1131, the references read as above where they can judge 1e-4, else the graded rods
# extrapolated from N = 800, 1600, 3200, or from 1600, 3200, 6400 where the first errs by more
# than 3e-6, and once more (runs up to N = 12 800) where the reference still keeps out an entry
# the atlas needs (an atlas angle's, or a held-out angle's that could set the margin); writes
# assets/release-atlas/graded-atlas.csv and graded-atlas.png and .svg. About two hours on 2
# cores (an estimate from the five runs that measured the committed rows, all against computed
# references, before the script read any: docs/measurements.md).
#
# `scripts/release-atlas.sh graded --until 5`: the graded rods' worst tip error to t = 5 from
# 40° up (below it their end rods spin after a second whip), which `--tolerance` reads for a
# release run from t = 3 to 5, against references refined towards 1e-5 at most once (runs up
# to N = 6400); writes assets/release-atlas/graded-atlas-t5.csv and its chart. About 15
# minutes of wall an angle, two at a time on 2 cores.
#
# `scripts/release-atlas.sh graded --add 1600`: each graded angle's entry at that one N, against a
# reference refined from N = 1600 until its own error is at most 1e-5 (runs up to N = 12 800),
# merged into the committed graded-atlas.csv (an entry already there at that N is replaced) and
# its chart redrawn. The committed entries at N = 1 600 were measured so: see
# docs/measurements.md for its CPU time.
set -euo pipefail
cd "$(dirname "$0")/.."
rods="${*:-}"
add=""
case "$rods" in
    "") name=atlas ;;
    graded) name=graded-atlas ;;
    "graded --until 5") name=graded-atlas-t5 ;;
    "graded --add "[0-9]*) name=graded-atlas; add="${rods##* }" ;;
    *) echo "usage: scripts/release-atlas.sh [graded [--until 5 | --add N]]" >&2; exit 2 ;;
esac
mkdir -p assets/release-atlas
csv="assets/release-atlas/$name.csv"
# The tolerance check's committed references (every atlas angle's), read where they can judge
# 1e-4 instead of computed; a reference to t = 5 is computed (they end at t = 3).
references=""
case "$rods" in
    *--until*) ;;
    *) references="--references assets/tolerance-check/references.csv" ;;
esac
cargo run --release --locked --quiet --example release_atlas -- $rods $references > "$csv.new"
if [ -n "$add" ]; then
    # The committed lines but those at N = $add, and the new ones, each angle's by N.
    { head -n 1 "$csv"
      { tail -n +2 "$csv" | awk -F, -v n="$add" '$3 != n'; tail -n +2 "$csv.new"; } \
          | sort -t, -k2,2g -k3,3n; } > "$csv.merged"
    mv "$csv.merged" "$csv.new"
fi
mv "$csv.new" "$csv"
chart="${rods%% --add*}"
cargo run --release --locked --quiet --example release_atlas_chart -- $chart
