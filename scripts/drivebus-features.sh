#!/usr/bin/env bash
# Every Cargo feature of drivebus builds on its own (without the default `std`), and so do no
# features and all of them: a user may pick any one. The feature list is read from the manifest,
# so a new feature is checked without editing this script. Then the pairs whose code is built only
# when both are on: the device side of a protocol (`server` with the protocol's feature) and the
# test doubles of a protocol (`testing` with it).
set -euo pipefail
cd "$(dirname "$0")/.."

features=$(cargo metadata --offline --no-deps --format-version 1 | python3 -c '
import json, sys
package = next(p for p in json.load(sys.stdin)["packages"] if p["name"] == "drivebus")
print(" ".join(sorted(f for f in package["features"] if f != "default")))
')
check() {
    echo "drivebus: $*"
    cargo check --quiet -p drivebus --lib "$@"
}
check --no-default-features
for feature in $features; do
    check --no-default-features --features "$feature"
done
for pair in server,modbus-core server,canopen server,srdo testing,modbus-core testing,canopen \
    testing,rs232 server,testing; do
    check --no-default-features --features "$pair"
done
check --all-features
