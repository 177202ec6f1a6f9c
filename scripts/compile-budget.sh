#!/usr/bin/env bash
# Compile-time budget of generated crates (a benchmark, not a test): cold and no-change rebuild
# times of each drive crate and of a synthetic 2,000-parameter description, the size of the
# generated source, and whether a no-change rebuild ran the generator. Prints a Markdown table.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$root/target/compile-budget"
mkdir -p "$work/synthetic/src"
cd "$root"

python3 scripts/synthetic_description.py 2000 > "$work/synthetic/device.toml"
cat > "$work/synthetic/Cargo.toml" <<TOML
[package]
name = "synthetic-drive"
version = "0.0.0"
edition = "2021"
[dependencies]
drivebus = { path = "$root/drivebus", default-features = false }
[build-dependencies]
drivegen = { path = "$root/codegen", default-features = false }
[workspace]
TOML
cat > "$work/synthetic/build.rs" <<'RS'
fn main() {
    drivegen::Builder::new("device.toml").compile().unwrap();
}
RS
cat > "$work/synthetic/src/lib.rs" <<'RS'
//! Synthetic 2,000-parameter drive.
#![no_std]
#![allow(missing_docs)]
include!(concat!(env!("OUT_DIR"), "/drive.rs"));
RS

seconds() { local start end; start=$(date +%s.%N); "$@" >/dev/null 2>&1; end=$(date +%s.%N); echo "$end - $start" | bc; }

measure() {  # name, manifest, package
    local name=$1 manifest=$2 package=$3 target=$4
    cargo build -q --manifest-path "$manifest" -p "$package" 2>/dev/null   # warm the dependencies
    cargo clean -q --manifest-path "$manifest" -p "$package" 2>/dev/null
    local cold; cold=$(seconds cargo build --manifest-path "$manifest" -p "$package")
    local out; out=$(ls -t "$target"/debug/build/"$package"-*/out/drive.rs | head -1)
    local before; before=$(stat -c %Y.%N "$out")
    local again; again=$(seconds cargo build --manifest-path "$manifest" -p "$package")
    local reran="no"; [ "$(stat -c %Y.%N "$out")" = "$before" ] || reran="yes"
    local lines; lines=$(wc -l < "$out"); local bytes; bytes=$(wc -c < "$out")
    printf '| %s | %.1f s | %.2f s | %s | %s lines, %s KiB |\n' "$name" "$cold" "$again" "$reran" "$lines" "$((bytes / 1024))"
}

echo "| crate | cold debug build | no-change rebuild | generator re-ran | generated source |"
echo "|---|---|---|---|---|"
for crate in drives/*/; do
    package=$(basename "$crate")
    measure "$package" "$root/Cargo.toml" "$package" "$root/target"
done
measure "synthetic (2,000 parameters)" "$work/synthetic/Cargo.toml" synthetic-drive "$work/synthetic/target"
