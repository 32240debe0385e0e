#!/usr/bin/env bash
# What rope says on a set of commands, timings masked, one file per command, into DIR:
# run it before and after a change that should not change the CLI's output, then
# `diff -r BEFORE AFTER`. Usage: scripts/cli-transcript.sh DIR [ROPE]
set -u
out=${1:?usage: scripts/cli-transcript.sh DIR [ROPE]}
rope=${2:-./target/release/rope}
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Wall and CPU times, ns per segment-step, rates and predicted costs vary run to run.
mask() {
    sed -E \
        -e 's/[0-9.]+ s wall/T s wall/g' \
        -e 's/[0-9.]+ s CPU/T s CPU/g' \
        -e 's/[0-9.]+ ns per segment-step/T ns per segment-step/g' \
        -e 's/[0-9.]+ s of CPU/T s of CPU/g' \
        -e 's/"(wall_seconds|cpu_seconds|ns_per_segment_step|pilot_seconds)": [0-9.e+-]+/"\1": T/g' \
        -e 's/[0-9.e+-]+ CPU s/T CPU s/g' \
        -e 's/\*\*[0-9.]+× more CPU\*\*/**R× more CPU**/g' \
        -e "s#$work#WORK#g"
}
n=0
case_() { # NAME ARGS…: run rope with ARGS, keep its exit status, stdout and stderr
    local name=$1
    shift
    n=$((n + 1))
    local file
    file=$(printf '%s/%02d-%s.txt' "$out" "$n" "$name")
    {
        echo "\$ rope $*" | mask
        "$rope" "$@" >"$work/stdout" 2>"$work/stderr"
        echo "exit $?"
        echo "--- stdout"
        if [ "$name" = stdout ]; then
            head -c 4 "$work/stdout" # an .rrd stream: its magic, not its timestamps
            echo
        else
            mask <"$work/stdout"
        fi
        echo "--- stderr"
        mask <"$work/stderr"
    } >"$file"
}
case_ default run --duration 5 --save "$work/a.rrd"
case_ diverged run --method seed,chain --angle 60 --duration 60 --save "$work/b.rrd"
case_ seed-alone-diverges run --method seed --duration 80 --save "$work/c.rrd"
case_ tolerance run --tolerance 1e-2 --duration 3 --save "$work/d.rrd"
case_ side-by-side run --method seed,chain,midpoint --duration 5 --save "$work/e.rrd"
case_ loop run --loop 2 --duration 2 --save "$work/f.rrd"
case_ summary run --duration 2 --save "$work/g.rrd" --summary "$work/g.json"
mask <"$work/g.json" >"$out/$(printf %02d $n)-summary.json"
case_ horizontal-seed run --method seed --angle 0 --save "$work/h.rrd"
case_ negative-dt run --dt -1 --save "$work/i.rrd"
case_ zero-duration run --duration 0 --save "$work/j.rrd"
case_ stdout run --duration 1 --stdout
case_ estimate-past run --method chain --segments 8 --tolerance 1e-1 --duration 4 --save "$work/k.rrd"
case_ study-refused study --segments 16 --dts 1e-3 --methods seed --angle 0 --out "$work/s1"
case_ study study --segments 8,16 --dts 2e-3,4e-3 --duration 2 --out "$work/s2"
case_ run-help run --help
case_ study-help study --help
echo "wrote $n transcripts to $out"
