#!/usr/bin/env bash
# Packages every published crate (all members but those with `publish = false`) and verifies that
# each builds from its own archive: `cargo package --workspace` builds the archives against a
# temporary local registry of each other (target/package/tmp-registry). The archives stay in
# target/package/*.crate for scripts/consumer.sh. Test and bench targets are left out of the
# packages on purpose (they need the workspace), so cargo's notes about them are not shown.
set -euo pipefail
cd "$(dirname "$0")/.."

internal=$(cargo metadata --offline --no-deps --format-version 1 | python3 -c '
import json, sys
for package in json.load(sys.stdin)["packages"]:
    if package["publish"] == []:
        print("--exclude=" + package["name"])
')
log=$(mktemp)
trap 'rm -f "$log"' EXIT
status=0
# shellcheck disable=SC2086 # one flag per word
cargo package --workspace $internal --allow-dirty >"$log" 2>&1 || status=$?
grep -v -e '^warning: ignoring \(test\|benchmark\) `' -e '^ *Compiling ' "$log" || true
exit "$status"
