#!/usr/bin/env bash
# Packages every published crate (all members but those with `publish = false`) and verifies that
# each builds from its own archive: `cargo package --workspace` builds the archives against a
# temporary local registry of each other (target/package-build/package/tmp-registry). The
# archives are copied to target/package/*.crate for scripts/consumer.sh. Test and bench targets
# are left out of the packages on purpose (they need the workspace), so cargo's notes about them
# are not shown. Cargo packages in dependency order: drivebus-model first (drivebus and drivegen
# pin it exactly), then drivebus and drivegen, drivesim, the drive crates and drivegen-cli; crates
# are published in the same order.
set -euo pipefail
cd "$(dirname "$0")/.."

metadata=$(cargo metadata --offline --no-deps --format-version 1)
internal=$(python3 -c '
import json, sys
for package in json.load(sys.stdin)["packages"]:
    if package["publish"] == []:
        print("--exclude=" + package["name"])
' <<<"$metadata")
# The archives are verified in their own target directory. Cargo takes a registry crate's build
# as final once made, and the temporary registry gives each crate the same name, version and
# source on every run: so earlier runs' builds of the published crates are removed there first,
# and so are the copies cargo unpacked from earlier archives under $CARGO_HOME/registry/src/.
export CARGO_TARGET_DIR=target/package-build
# Each archive is its own workspace there, without this workspace's profile: without debug info
# its dependencies build and link faster, and the check only needs them to build.
export CARGO_PROFILE_DEV_DEBUG=false
published=$(python3 -c '
import json, sys
for package in json.load(sys.stdin)["packages"]:
    if package["publish"] != []:
        print(package["name"], package["version"])
' <<<"$metadata")
while read -r name version; do
    rm -rf "${CARGO_HOME:-$HOME/.cargo}"/registry/src/-*/"$name-$version"
    cargo clean --quiet -p "$name" 2>/dev/null || true
done <<<"$published"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
status=0
# shellcheck disable=SC2086 # one flag per word
cargo package --workspace $internal --allow-dirty >"$log" 2>&1 || status=$?
grep -v -e '^warning: ignoring \(test\|benchmark\) `' -e '^ *Compiling ' "$log" || true
# The archives where scripts/consumer.sh and the docs expect them.
mkdir -p target/package
cp "$CARGO_TARGET_DIR"/package/*.crate target/package/
exit "$status"
