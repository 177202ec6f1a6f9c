#!/usr/bin/env bash
# A local campaign: builds the targets once, then runs every target (or those named) for
# SECONDS_PER_TARGET seconds each on one core, growing fuzz/corpus/<target>, and prints each
# target's final libFuzzer line and stats. docs/reliability.md says how to run a longer one.
set -uo pipefail
cd "$(dirname "$0")"
seconds="${SECONDS_PER_TARGET:-90}"
export TMPDIR="$PWD/target/tmp"
mkdir -p "$TMPDIR"
cargo +nightly fuzz build --debug-assertions || exit 1
bin="target/x86_64-unknown-linux-gnu/release"
targets=("$@")
[ ${#targets[@]} -gt 0 ] || mapfile -t targets < <(cargo +nightly fuzz list)
for target in "${targets[@]}"; do
    mkdir -p "corpus/$target" "artifacts/$target"
    "$bin/$target" "corpus/$target" "seeds/$target" -artifact_prefix="artifacts/$target/" \
        -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=1 >"$TMPDIR/$target.campaign.log" 2>&1
    status=$?
    echo "$target exit=$status $(grep -a -E '^#[0-9]+' "$TMPDIR/$target.campaign.log" | tail -1)"
    grep -a -E '^stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb)' \
        "$TMPDIR/$target.campaign.log"
    grep -a -m1 -A2 -E 'panicked at|ERROR: libFuzzer|ERROR: AddressSanitizer' \
        "$TMPDIR/$target.campaign.log"
done
