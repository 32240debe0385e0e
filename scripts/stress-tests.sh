#!/usr/bin/env bash
# Runs the whole test suite N times in a row, the even-numbered runs with a CPU hog on every
# core, and prints which tests failed in which run. A test that can fail by chance shows here.
#
#   scripts/stress-tests.sh 20        # 20 runs: 10 idle, 10 with every core busy
#
# Exit status: 0 if every run passed, 1 otherwise. Logs: target/stress/run-K.log.
set -uo pipefail
cd "$(dirname "$0")/.."
runs="${1:-20}"
if ! [[ "$runs" =~ ^[1-9][0-9]*$ ]]; then
    echo "usage: $0 N   (N ≥ 1 runs of cargo test --release)" >&2
    exit 2
fi
mkdir -p target/stress
echo "building the tests once…"
cargo test --release --no-run --quiet || exit 1

hogs=()
stop_hogs() {
    if ((${#hogs[@]})); then kill "${hogs[@]}" 2>/dev/null; wait "${hogs[@]}" 2>/dev/null; fi
    hogs=()
}
trap stop_hogs EXIT

failed_runs=0
for ((k = 1; k <= runs; k++)); do
    load="idle"
    if ((k % 2 == 0)); then
        load="every core busy"
        for ((c = 0; c < $(nproc); c++)); do
            yes > /dev/null &
            hogs+=($!)
        done
    fi
    log="target/stress/run-$k.log"
    started=$SECONDS
    cargo test --release > "$log" 2>&1
    status=$?
    stop_hogs
    took=$((SECONDS - started))
    if ((status == 0)); then
        echo "run $k/$runs ($load): passed in ${took} s"
    else
        failed_runs=$((failed_runs + 1))
        echo "run $k/$runs ($load): FAILED in ${took} s; see $log"
        grep -E "^test .* FAILED$|^    [a-z_0-9:]+$" "$log" | sed 's/^/    /' | sort -u
    fi
done
echo "$((runs - failed_runs)) passed, $failed_runs failed"
((failed_runs == 0))
