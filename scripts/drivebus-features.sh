#!/usr/bin/env bash
# Every Cargo feature of drivebus and of drivebus-model (the vocabulary under it) builds on its
# own (without the default `std`), and so do no features and all of them: a user may pick any
# one. The feature lists are read from the manifests, so a new feature is checked without editing
# this script. Then the pairs of drivebus whose code is built only when both are on: the device
# side of a protocol (`server` with the protocol's feature) and the test doubles of a protocol
# (`testing` with it), and the async layer's (`async` with `canopen`: the async SDO client;
# `tokio` with `canopen`, `socketcan` or `serial`: the tokio CAN interfaces and serial stream).
set -euo pipefail
cd "$(dirname "$0")/.."

# The checks are independent: they are listed first, then run in JOBS lanes (default: the number
# of cores) side by side. A check of one crate keeps about one core busy (rustc's front end), so
# the lanes take about 1/JOBS of the time one after the other would. Each lane has its own target
# directory: cargo lets one build at a time use a target directory.
checks=()
metadata=$(cargo metadata --offline --no-deps --format-version 1)
for crate in drivebus-model drivebus; do
    features=$(python3 -c '
import json, sys
package = next(p for p in json.load(sys.stdin)["packages"] if p["name"] == sys.argv[1])
print(" ".join(sorted(f for f in package["features"] if f != "default")))
' "$crate" <<<"$metadata")
    checks+=("$crate --no-default-features")
    for feature in $features; do
        checks+=("$crate --no-default-features --features $feature")
    done
    checks+=("$crate --all-features")
done
for pair in server,modbus-core server,canopen server,srdo testing,modbus-core testing,canopen \
    testing,rs232 server,testing async,canopen tokio,canopen tokio,socketcan tokio,serial; do
    checks+=("drivebus --no-default-features --features $pair")
done
# The async layer and the Modbus core on a bare-metal target, as an embassy firmware would build
# them: proves `async` names no executor and needs no std.
no_std_target=thumbv7em-none-eabihf
rustup target list --installed | grep -qx "$no_std_target" || rustup target add "$no_std_target"
for features in async async,modbus-core; do
    checks+=("drivebus --no-default-features --features $features --target $no_std_target")
done

# Lane `lane` of `jobs`: every jobs-th check from the lane's index, stopping at the first failure.
lane() {
    local lane=$1 jobs=$2 i crate args
    for ((i = lane; i < ${#checks[@]}; i += jobs)); do
        read -r crate args <<<"${checks[$i]}"
        echo "$crate: $args"
        # shellcheck disable=SC2086 # one flag per word
        cargo check --quiet -p "$crate" --lib $args || return 1
    done
}
jobs="${JOBS:-$(nproc)}"
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
pids=()
for ((l = 0; l < jobs; l++)); do
    # Lane 0 builds in the usual target directory, the others in folders of it.
    dir=${CARGO_TARGET_DIR:-target}
    [ "$l" -eq 0 ] || dir=$dir/drivebus-features-$l
    CARGO_TARGET_DIR=$dir lane "$l" "$jobs" >"$logs/$l" 2>&1 &
    pids+=("$!")
done
status=0
for ((l = 0; l < jobs; l++)); do
    wait "${pids[$l]}" || status=1
    cat "$logs/$l"
done
[ "$status" -eq 0 ] || echo "drivebus-features: a check failed (above)" >&2
exit "$status"
