#!/usr/bin/env bash
# Build-time benchmark of the drive crates, comparing source trees (a benchmark, not a test):
#   scripts/build-times.sh ROUNDS TREE...    e.g. scripts/build-times.sh 2 /tmp/before .
# For each tree, in alternating rounds so both see the same machine load:
#   * the lines of each drive crate's generated source;
#   * each drive crate's own debug and release build (its dependencies warm, the crate cleaned);
#   * a drive crate built from nothing (an empty target directory): dependencies, generator and
#     all (the generator used to compile the runtime for the host as well);
#   * the generator's own time on all shipped descriptions (`cargo bench -p drivegen --bench
#     generate`, the "check + emit" median).
# Prints one Markdown table per measure; each tree's target directory is its own
# (target/build-times under the tree), so the trees do not share artifacts.
set -euo pipefail
rounds=$1
shift
trees=()
for tree in "$@"; do trees+=("$(cd "$tree" && pwd)"); done
drives=(lafert-smartris ezwheel-swd lenze-smd kinco-fd)
results=$(mktemp -d)

seconds() {
    local start end
    start=$(date +%s.%N)
    "$@" >/dev/null 2>&1
    end=$(date +%s.%N)
    echo "$end - $start" | bc
}

generated_lines() {  # tree, package
    local out
    out=$(ls -t "$1"/target/build-times/debug/build/"$2"-*/out/drive.rs | head -1)
    wc -l <"$out"
}

crate_build() {  # tree, package, profile flag ("" or --release)
    local tree=$1 package=$2 profile=$3
    (cd "$tree" && cargo build -q $profile -p "$package" 2>/dev/null)  # warm the dependencies
    (cd "$tree" && cargo clean -q $profile -p "$package" 2>/dev/null)
    (cd "$tree" && seconds cargo build $profile -p "$package")
}

from_nothing() {  # tree, package
    local tree=$1 package=$2 fresh
    fresh=$(mktemp -d)
    local start end
    start=$(date +%s.%N)
    (cd "$tree" && CARGO_TARGET_DIR=$fresh/target cargo build -q -p "$package" >/dev/null 2>&1)
    end=$(date +%s.%N)
    rm -rf "$fresh"
    echo "$end - $start" | bc
}

generator_ms() {  # tree
    (cd "$1" && cargo bench -q -p drivegen --bench generate -- --warm-up-time 1 \
        --measurement-time 3 'check \+ emit Rust for all' 2>/dev/null) |
        sed -n 's/.*time: *\[[^ ]* [^ ]* \([^ ]*\) \([^ ]*\) .*/\1 \2/p' | head -1
}

export CARGO_TARGET_DIR
for round in $(seq "$rounds"); do
    for tree in "${trees[@]}"; do
        key=$(echo "$tree" | md5sum | cut -c1-8)
        CARGO_TARGET_DIR=$tree/target/build-times
        for package in "${drives[@]}"; do
            echo "$(crate_build "$tree" "$package" "")" >>"$results/$key.$package.debug"
            echo "$(crate_build "$tree" "$package" --release)" >>"$results/$key.$package.release"
            generated_lines "$tree" "$package" >"$results/$key.$package.lines"
        done
        unset CARGO_TARGET_DIR
        from_nothing "$tree" lafert-smartris >>"$results/$key.cold"
        export CARGO_TARGET_DIR=$tree/target/build-times
        generator_ms "$tree" >>"$results/$key.generator"
        echo "round $round done: $tree" >&2
    done
done

median() { sort -n | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

header="| tree |"
rule="|---|"
for package in "${drives[@]}"; do header+=" $package |"; rule+="---|"; done
for measure in lines debug release; do
    echo
    echo "$measure (median of $rounds)"
    echo "$header"
    echo "$rule"
    for tree in "${trees[@]}"; do
        key=$(echo "$tree" | md5sum | cut -c1-8)
        row="| $tree |"
        for package in "${drives[@]}"; do
            row+=" $(median <"$results/$key.$package.$measure") |"
        done
        echo "$row"
    done
done
echo
echo "| tree | lafert-smartris from nothing (s, median) | generator, check + emit all (median) |"
echo "|---|---|---|"
for tree in "${trees[@]}"; do
    key=$(echo "$tree" | md5sum | cut -c1-8)
    echo "| $tree | $(median <"$results/$key.cold") | $(head -1 "$results/$key.generator") |"
done
rm -rf "$results"
