#!/usr/bin/env bash
# `rope study` split into shards and run by GNU parallel on this machine: the reference once,
# then the shards (each on one core), then the merge.
#
#   scripts/study-parallel.sh OUT SHARDS [study flags…]
#   e.g. scripts/study-parallel.sh study 8
set -euo pipefail
out=${1:?give the output directory}
shards=${2:?give the number of shards}
shift 2
rope=${ROPE:-target/release/rope}
command -v parallel >/dev/null || { echo "GNU parallel is not installed (apt-get install parallel)" >&2; exit 1; }
"$rope" study "$@" --reference-only --out "$out/shards/reference"
RAYON_NUM_THREADS=1 parallel --halt now,fail=1 \
    "$rope" study "$@" --shard {}/"$shards" \
    --reference "$out/shards/reference/reference.json" --out "$out/shards/{}" \
    ::: $(seq 0 $((shards - 1)))
"$rope" study --merge $(seq -f "$out/shards/%g" 0 $((shards - 1))) --out "$out"
