#!/usr/bin/env bash
# Every Cargo feature of drivebus builds on its own (without the default `std`), and so do no
# features and all of them: a user may pick any one. The feature list is read from the manifest,
# so a new feature is checked without editing this script.
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
check --all-features
