#!/usr/bin/env bash
# Runs the README's "Describe your own drive" walk-through exactly as written (its first ```sh
# block), in a temporary folder holding a vendor.eds, with this checkout's `drivegen` on PATH:
# `drivegen new` writes crates that build at once, from the skeleton and from an EDS. The crates
# build in target/consumer/, shared with scripts/consumer.sh and kept between runs.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

walkthrough=$(awk '
    /^## Describe your own drive/ { section = 1; next }
    section && /^```sh/ { block = 1; next }
    block && /^```/ { exit }
    block { print }
' README.md)
[[ -n $walkthrough ]] || { echo "new-drive: no walk-through in README.md" >&2; exit 1; }

# The `drivegen` it runs: $DRIVEGEN if set (.ci/test passes the one its `cargo test` build just
# made: `-p drivegen-cli` resolves other features than that build, so building it here again took
# most of this script's minute), else this checkout's, built here.
if [[ -n ${DRIVEGEN:-} ]]; then
    [[ -x $DRIVEGEN ]] || { echo "new-drive: DRIVEGEN=$DRIVEGEN is not an executable" >&2; exit 1; }
    [[ $(basename "$DRIVEGEN") == drivegen ]] ||
        { echo "new-drive: DRIVEGEN must name a file drivegen (the walk-through runs it by name)" >&2; exit 1; }
    bin_dir=$(cd "$(dirname "$DRIVEGEN")" && pwd)
else
    cargo build --offline --quiet -p drivegen-cli
    bin_dir=$root/target/debug
fi
folder=$(mktemp -d)
trap 'rm -rf "$folder"' EXIT
cp codegen/tests/eds/access_types.eds "$folder/vendor.eds"
(
    cd "$folder"
    # Offline: the crates the workspace build downloaded are enough.
    export PATH="$bin_dir:$PATH" CARGO_TARGET_DIR="$root/target/consumer" CARGO_NET_OFFLINE=true \
        CARGO_PROFILE_DEV_DEBUG=false
    set -x
    eval "$walkthrough"
)
echo "new-drive: the README walk-through ran as written"
