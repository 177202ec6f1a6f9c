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

metadata=$(cargo metadata --offline --no-deps --format-version 1)
for crate in drivebus-model drivebus; do
    features=$(python3 -c '
import json, sys
package = next(p for p in json.load(sys.stdin)["packages"] if p["name"] == sys.argv[1])
print(" ".join(sorted(f for f in package["features"] if f != "default")))
' "$crate" <<<"$metadata")
    check() {
        echo "$crate: $*"
        cargo check --quiet -p "$crate" --lib "$@"
    }
    check --no-default-features
    for feature in $features; do
        check --no-default-features --features "$feature"
    done
    check --all-features
done
# `check` still names drivebus, the loop's last crate.
for pair in server,modbus-core server,canopen server,srdo testing,modbus-core testing,canopen \
    testing,rs232 server,testing async,canopen tokio,canopen tokio,socketcan tokio,serial; do
    check --no-default-features --features "$pair"
done
# The async layer and the Modbus core on a bare-metal target, as an embassy firmware would build
# them: proves `async` names no executor and needs no std.
no_std_target=thumbv7em-none-eabihf
rustup target list --installed | grep -qx "$no_std_target" || rustup target add "$no_std_target"
for features in async async,modbus-core; do
    echo "drivebus for $no_std_target: $features"
    cargo check --quiet -p drivebus --lib --no-default-features --features "$features" --target "$no_std_target"
done
