#!/usr/bin/env bash
# A bounded fuzz of the `rope` command line: random combinations of flags and values, each
# run headless (--save to a scratch file) with a short duration. Every exit must be 0 (ran),
# 2 (bad input, named), 3 (diverged, said when), or 1 with a stated error; never a panic
# (exit 101), a signal (128 + n) or a run that does not end within 30 s (124).
#
#   scripts/cli-fuzz.sh [--seed S] [--runs N]      # defaults: a random seed, 1000 runs
#
# CI runs it with a fixed seed. Prints the seed, each failing command, and a count.
set -uo pipefail
cd "$(dirname "$0")/.."
seed=$RANDOM
runs=1000
while (($#)); do
    case "$1" in
        --seed) seed="$2"; shift 2 ;;
        --runs) runs="$2"; shift 2 ;;
        *) echo "usage: $0 [--seed S] [--runs N]" >&2; exit 2 ;;
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

echo "cli-fuzz: seed $seed, $runs runs"
failed=0
declare -A exits=()
started=$SECONDS
for ((r = 1; r <= runs; r++)); do
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
    ((RANDOM % 3 == 0)) && add --method seed chain rattle midpoint "" "seed,chain" "chain,chain"
    # Each scene with its own flags, mostly (a flag of the other scene is refused by name).
    if ((RANDOM % 4 == 0)); then
        args+=(--scene mode)
        add --mode-number 0 1 2 4 5 "1,2"
        add --amplitude "${numbers[@]}"
        ((RANDOM % 8 == 0)) && add --angle "${numbers[@]}"
    else
        ((RANDOM % 3 == 0)) && add --angle "${numbers[@]}" "0,30" "30,60,90"
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
    exits[$code]=$((${exits[$code]:-0} + 1))
    ok=false
    case $code in
        0 | 2 | 3) ok=true ;;
        1) grep -q "rope: error:" "$scratch/err" && ok=true ;;
    esac
    grep -q "panicked" "$scratch/err" && ok=false
    if ! $ok; then
        failed=$((failed + 1))
        echo "FAILED (exit $code): rope ${args[*]}"
        sed 's/^/    /' "$scratch/err" | tail -5
    fi
done
tally=""
for code in $(printf '%s\n' "${!exits[@]}" | sort -n); do tally+=" exit $code: ${exits[$code]};"; done
echo "cli-fuzz:$tally"
echo "cli-fuzz: seed $seed, $((SECONDS - started)) s"
echo "cli-fuzz: $((runs - failed)) passed, $failed failed"
((failed == 0))
