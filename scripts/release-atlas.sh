#!/usr/bin/env bash
# The release atlas `--tolerance` reads for a release run to t ≤ 3: the worst tip error, at
# every 1/3000 of a time unit, of the rods (the chain at its tolerance step) per release angle
# (0°, 10°, …, 90°, and the held-out 5°, 15°, …, 85°) and N = 16 … 566, against the tolerance
# check's references read from assets/tolerance-check/references.csv (0° to 90°), else (the
# held-out angles) computed as the check computes one (the graded rods from 20° up, else the
# chain) from N = 800, 1600, 3200, or from 1600, 3200, 6400 where the first errs by more than
# 3e-6; below 20°, where no other rods may be chosen, on to N = 1131.
# Writes assets/release-atlas/atlas.csv (read at build time: rebuild afterwards) and its chart,
# atlas.png and atlas.svg. With ROPE_RUN_CACHE=DIR the references' runs are kept and shared
# with the graded atlas: see docs/measurements.md for the time it took.
#
# `scripts/release-atlas.sh graded`: the same of the graded rods (`--method graded`) from 20°
# up to N = 1600, the references read as above, else computed as above (refined once at most);
# writes assets/release-atlas/graded-atlas.csv and graded-atlas.png and .svg.
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
#
# `scripts/release-atlas.sh graded --redo 50,60 PATH`: those graded angles' rows measured again,
# on to N = 2263, against the least-erring reference among the check's and PATH's (a references
# file or folder, e.g. assets/reference-convergence/graded-references-25600, whose own errors
# of 4.5e-6 and 8.4e-6 can judge 1e-4 there), replacing their lines in the committed
# graded-atlas.csv, and its chart redrawn. About two minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
rods="${*:-}"
add=""
redo=""
more=""
case "$rods" in
    "") name=atlas ;;
    graded) name=graded-atlas ;;
    "graded --until 5") name=graded-atlas-t5 ;;
    "graded --add "[0-9]*) name=graded-atlas; add="${rods##* }" ;;
    "graded --redo "[0-9]*" "?*)
        name=graded-atlas; set -- $rods; redo="$3"; more="$4"; rods="graded $redo" ;;
    *) echo "usage: scripts/release-atlas.sh [graded [--until 5 | --add N | --redo ANGLES PATH]]" >&2; exit 2 ;;
esac
mkdir -p assets/release-atlas
csv="assets/release-atlas/$name.csv"
# The tolerance check's committed references (every atlas angle's), read instead of computed
# (--read-any: at every 1/3000 they err by up to 2.1e-5 from 70° and 80°, where one computed
# here from runs up to N = 6400 errs by up to 5.9e-5); a reference to t = 5 is computed (they
# end at t = 3). The graded rods' computed references (the held-out angles') are refined once
# (runs up to N = 6400), and their rows measured to N = 1600.
references=""
to=1600
[ -z "$redo" ] || to=2263
case "$rods" in
    *--until*) ;;
    graded | "graded "[0-9]*) references="--read-any --refine-once --to $to --references assets/tolerance-check/references.csv${more:+ --references $more}" ;;
    *) references="--read-any --references assets/tolerance-check/references.csv" ;;
esac
cargo run --release --locked --quiet --example release_atlas -- $rods $references > "$csv.new"
if [ -n "$add" ]; then
    # The committed lines but those at N = $add, and the new ones, each angle's by N.
    { head -n 1 "$csv"
      { tail -n +2 "$csv" | awk -F, -v n="$add" '$3 != n'; tail -n +2 "$csv.new"; } \
          | sort -t, -k2,2g -k3,3n; } > "$csv.merged"
    mv "$csv.merged" "$csv.new"
fi
if [ -n "$redo" ]; then
    # The committed lines in their order, each redone angle's replaced by its new ones.
    awk -F, 'NR == FNR { if (FNR > 1) fresh[$2] = fresh[$2] $0 "\n"; next }
             !($2 in fresh) { print; next }
             !($2 in done) { printf "%s", fresh[$2]; done[$2] = 1 }' "$csv.new" "$csv" > "$csv.merged"
    mv "$csv.merged" "$csv.new"
fi
mv "$csv.new" "$csv"
chart="${rods%% --add*}"
[ -z "$redo" ] || chart=graded
cargo run --release --locked --quiet --example release_atlas_chart -- $chart
