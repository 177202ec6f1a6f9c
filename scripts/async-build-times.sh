#!/usr/bin/env bash
# Build time of a drive crate with and without its `async` feature (issue 30; a benchmark, not
# a test): scripts/async-build-times.sh ROUNDS [CRATE]   (default lafert-smartris)
# Debug builds of the crate alone, its dependencies warm and the crate cleaned before each
# build; within a round the two variants alternate, the order swapping every round, so other
# load on the machine hits both alike. Prints one Markdown row per round and the load average.
set -euo pipefail
rounds=${1:-2}
crate=${2:-lafert-smartris}

seconds() {
    local start end
    start=$(date +%s.%N)
    "$@" >/dev/null 2>&1
    end=$(date +%s.%N)
    printf '%.2f' "$(echo "$end - $start" | bc)"
}

build() {  # features flag ("" or "--features async")
    # shellcheck disable=SC2086
    cargo build -q -p "$crate" $1 2>/dev/null  # warm the dependencies
    cargo clean -q -p "$crate" 2>/dev/null
    # shellcheck disable=SC2086
    seconds cargo build -p "$crate" $1
}

echo "| round | without async (s) | with async (s) | with / without | load average |"
echo "| ---: | ---: | ---: | ---: | --- |"
for round in $(seq "$rounds"); do
    if ((round % 2)); then
        without=$(build "")
        with=$(build "--features async")
    else
        with=$(build "--features async")
        without=$(build "")
    fi
    ratio=$(printf '%.2f' "$(echo "scale=4; $with / $without" | bc)")
    echo "| $round | $without | $with | $ratio | $(cut -d' ' -f1-3 /proc/loadavg) |"
done
