#!/usr/bin/env bash
# The proof that `cargo add lafert-smartris` works: a fresh Cargo project in a temporary folder,
# outside the workspace, that depends on the packaged crates only — the archives
# scripts/package.sh leaves in target/package/, unpacked and named in [patch.crates-io], the
# stand-in for crates.io until they are published. It is built and run: it reads typed values
# from a simulated Lafert Smartris whose description comes from the packaged drive crate.
# Its dependencies build in target/consumer/ (without debug info), kept between runs.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

project=$(mktemp -d)
trap 'rm -rf "$project"' EXIT
mkdir -p "$project/crates" "$project/src"

patches=""
# drivebus-model too: drivebus and drivegen depend on it, pinned to the packaged version.
for crate in drivebus-model drivebus drivegen drivesim lafert-smartris; do
    version=$(cargo pkgid --offline -p "$crate" | sed 's/.*[#@]//')
    archive="target/package/$crate-$version.crate"
    [[ -f $archive ]] || { echo "consumer: no $archive; run scripts/package.sh first" >&2; exit 1; }
    # Unpacked with the time of unpacking: cargo gives archived files fixed times, and a build of
    # an earlier archive of the same version, kept in target/consumer, would pass for up to date.
    tar -xzf "$archive" -C "$project/crates" --touch
    patches+="$crate = { path = \"crates/$crate-$version\" }"$'\n'
done

cat > "$project/Cargo.toml" <<TOML
[package]
name = "drive-consumer"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
lafert-smartris = "0.1"
drivebus = { version = "0.1", features = ["modbus"] }
drivesim = "0.1"

# The packaged crates, as crates.io will serve them.
[patch.crates-io]
$patches
# Not part of any enclosing workspace.
[workspace]
TOML
cp scripts/consumer/main.rs "$project/src/main.rs"
# The crates.io versions the workspace is tested with (cargo drops the entries it does not need).
cp Cargo.lock "$project/Cargo.lock"

description=$(echo "$project"/crates/lafert-smartris-*/descriptions/lafert-smartris)
# Offline: the lock pins crates the workspace build has already downloaded.
output=$(cd "$project" && CARGO_TARGET_DIR="$root/target/consumer" CARGO_PROFILE_DEV_DEBUG=false \
    cargo run --offline --quiet -- "$description")
expected=$'bus_dc_link Volts(49.5)\noperation_mode velocity'
if [[ $output != "$expected" ]]; then
    printf 'consumer: expected\n%s\ngot\n%s\n' "$expected" "$output" >&2
    exit 1
fi
echo "consumer: a project outside the workspace read typed values through the packaged crates"
