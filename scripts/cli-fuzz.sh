#!/usr/bin/env bash
# A bounded fuzz of the `rope` command line: random combinations of flags and values, each
# run headless (--save to a scratch file) with a short duration. Every exit must be 0 (ran),
# 2 (bad input, named), 3 (diverged, said when), or 1 with a stated error; never a panic
# (exit 101), a signal (128 + n) or a run that does not end within 30 s (124).
# With --study, the same for `rope study`: small grids of odd flags, each written to a
# scratch folder; it must end within 60 s (a study whose every run was refused once spun
# for ever drawing a chart of nothing).
#
#   scripts/cli-fuzz.sh [--seed S] [--runs N] [--study]   # defaults: a random seed, 1000 runs
#
# CI runs it with a fixed seed. Prints the seed, each failing command, and a count.
set -uo pipefail
cd "$(dirname "$0")/.."
seed=$RANDOM
runs=1000
study=false
while (($#)); do
    case "$1" in
        --seed) seed="$2"; shift 2 ;;
        --runs) runs="$2"; shift 2 ;;
        --study) study=true; shift ;;
        *) echo "usage: $0 [--seed S] [--runs N] [--study]" >&2; exit 2 ;;
    esac
done
RANDOM=$seed
rope=target/release/rope
[[ -x $rope ]] || cargo build --release --quiet || exit 1
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# Sets $REPLY to one of its arguments. Not `$(…)`: bash reseeds RANDOM in a subshell, and
# the run would no longer follow from the seed.
pick() {
    local values=("$@")
    REPLY="${values[RANDOM % ${#values[@]}]}"
}
# Adds a flag with a value picked from the rest of the arguments.
add() {
    local flag="$1"
    shift
    pick "$@"
    args+=("$flag" "$REPLY")
}
numbers=(0 -1 1 2 3 0.5 1e-3 1e-9 1e300 -1e300 inf -inf nan NaN 1e-320 x "" 30 90 91 45.5)
counts=(0 1 2 3 4 5 10 100 1000 10000 100000000 18446744073709551615 -3 1.5 x "")
# Short enough to finish in seconds even at 10⁵ segments; `inf` would never end.
durations=(0 0.001 0.01 0.02 -1 nan 1e300 "")
steps=(0 -1 1 0.5 1e-3 1e-4 5e-3 1e-300 inf nan x "")

# The flags of a small `rope study`, odd values among them; sets `args`.
study_args() {
    args=(study --out "$scratch/study")
    # Sane values mostly (so that most studies run and draw their charts), odd ones besides.
    if ((RANDOM % 4)); then add --segments 4 8 16 32 "8,16" "16,8" "4,8,16,32"; else
        add --segments "16,16" 0 -4 1 x "" 100000000; fi
    if ((RANDOM % 4)); then add --dts 1e-3 3e-2 1e-2 "1e-3,3e-3" 0.3 1; else
        add --dts "1e-3,1e-3" 0 -1e-3 nan inf x "" 1e-300; fi
    ((RANDOM % 2)) && add --methods seed chain graded rattle midpoint "seed,chain" "chain,graded" "seed,seed" x ""
    ((RANDOM % 2)) && add --duration 0.1 0.3 1 0.1 0.3 1 0 -1 nan inf 1e300 x
    ((RANDOM % 3 == 0)) && add --reference-segments 4 8 16 64 64 7 0 -2 x
    ((RANDOM % 3 == 0)) && add --angle 0 1 30 90 30 60 91 -5 nan x
    ((RANDOM % 6 == 0)) && args+=(--scene mode) && add --mode-number 1 2 0 && add --amplitude 0.05 0 nan
    ((RANDOM % 12 == 0)) && args+=(--scene fold) && add --gap 0.04 0 nan
    ((RANDOM % 12 == 0)) && args+=(--scene shake) && add --frequency 2 0.6 1.2024 0 nan
    ((RANDOM % 6 == 0)) && add --max-memory 1MB 100MB 1KB 50% 0 x
    ((RANDOM % 8 == 0)) && add --save "$scratch/study.rrd" /dev/null/s.rrd
    true
}

# Counts exit $code of `rope ${args[@]}` and says if it failed: an exit among the arguments
# (`judge 0 2`), or 1 with a stated error, passes; any other, or a panic, fails.
judge() {
    exits[$code]=$((${exits[$code]:-0} + 1))
    local ok=false
    if [[ " $* " == *" $code "* ]]; then
        ok=true
    elif ((code == 1)) && grep -q "rope: error:" "$scratch/err"; then
        ok=true
    fi
    grep -q "panicked" "$scratch/err" && ok=false
    if ! $ok; then
        failed=$((failed + 1))
        echo "FAILED (exit $code): rope ${args[*]}"
        sed 's/^/    /' "$scratch/err" | tail -5
    fi
}

what=runs
$study && what="study runs"
echo "cli-fuzz: seed $seed, $runs $what"
failed=0
declare -A exits=()
started=$SECONDS
for ((r = 1; r <= runs; r++)); do
    if $study; then
        study_args
        timeout 60 "$rope" "${args[@]}" > /dev/null 2> "$scratch/err"
        code=$?
        [[ -n ${FUZZ_VERBOSE:-} ]] && echo "exit $code: rope ${args[*]}: $(grep -m1 'bad input\|error' "$scratch/err")"
        judge 0 2
        continue
    fi
    # --yes lets a run of years start, as asked: it goes only with a run that ends.
    args=(run --save "$scratch/x.rrd")
    if ((RANDOM % 8 == 0)); then
        args+=(--yes)
        add --duration 0 0.001 0.01
        ((RANDOM % 2)) && add --dt 1e-3 1e-4 5e-3
    else
        add --duration "${durations[@]}"
        ((RANDOM % 2)) && add --dt "${steps[@]}"
    fi
    ((RANDOM % 2)) && add --segments "${counts[@]}"
    ((RANDOM % 3 == 0)) && add --method seed chain graded rattle midpoint "" "seed,chain" "chain,chain"
    # Each scene with its own flags, mostly (a flag of the other scene is refused by name).
    if ((RANDOM % 4 == 0)); then
        args+=(--scene mode)
        add --mode-number 0 1 2 4 5 "1,2"
        add --amplitude "${numbers[@]}"
        ((RANDOM % 8 == 0)) && add --angle "${numbers[@]}"
    elif ((RANDOM % 5 == 0)); then
        args+=(--scene fold)
        ((RANDOM % 2)) && add --gap "${numbers[@]}" 0.02 0.04 0.63 0.64
        ((RANDOM % 8 == 0)) && add --angle "${numbers[@]}"
    elif ((RANDOM % 5 == 0)); then
        args+=(--scene shake)
        ((RANDOM % 2)) && add --amplitude "${numbers[@]}" 1e-3 0.01 0.05 0.06
        if ((RANDOM % 3)); then
            ((RANDOM % 2)) && add --frequency "${numbers[@]}" 1.2024 2 "0.6,2" 20 21
        else
            add --sweep 0.2..5:3 1..2 5..0.2 0.2..5:1 0..5 0.2..30 x "" 1..2:x 0.5..0.6:50
        fi
        ((RANDOM % 3 == 0)) && add --from steady rest x
        ((RANDOM % 8 == 0)) && add --gap "${numbers[@]}"
    else
        ((RANDOM % 3 == 0)) && add --angle "${numbers[@]}" "0,30" "30,60,90"
        ((RANDOM % 12 == 0)) && add --gap 0.02 nan
        ((RANDOM % 12 == 0)) && add --frequency 2 nan
    fi
    ((RANDOM % 4 == 0)) && add --log-rate "${numbers[@]}" 60 1000
    ((RANDOM % 5 == 0)) && add --tolerance "${numbers[@]}" 1e-2 3e-3 1e-12
    ((RANDOM % 5 == 0)) && add --realtime 100 1000 0 -1 nan
    ((RANDOM % 6 == 0)) && add --loop 1 2 0 -1 x
    ((RANDOM % 6 == 0)) && add --max-memory 1MB 100MB 64GB 50% 0 x
    ((RANDOM % 6 == 0)) && add --summary "$scratch/s.json" /dev/null/s.json
    ((RANDOM % 8 == 0)) && args+=(--allow-unstable)
    timeout 30 "$rope" "${args[@]}" > /dev/null 2> "$scratch/err"
    code=$?
    judge 0 2 3 4
done
tally=""
for code in $(printf '%s\n' "${!exits[@]}" | sort -n); do tally+=" exit $code: ${exits[$code]};"; done
echo "cli-fuzz:$tally"
echo "cli-fuzz: seed $seed, $((SECONDS - started)) s"
echo "cli-fuzz: $((runs - failed)) passed, $failed failed"
((failed == 0))
