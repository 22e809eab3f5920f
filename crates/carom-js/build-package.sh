#!/usr/bin/env bash
# Builds the npm package carom-js (the physics core compiled to WebAssembly, its JavaScript
# glue and TypeScript types) into a folder (default target/carom-js/package) and packs it
# with `npm pack` beside that folder (target/carom-js/carom-js-VERSION.tgz), then prints the
# module's and the tarball's sizes. Install the tarball with `npm install PATH.tgz`.
# Like the web site's build it adds the wasm32 target and the matching wasm-bindgen command
# line when they are missing (scripts/wasm-bindgen-cli.sh).
set -euo pipefail
cd "$(dirname "$0")/../.."
out="${1:-target/carom-js/package}"
target_dir="${CARGO_TARGET_DIR:-target}"

rustup target list --installed | grep -qx wasm32-unknown-unknown \
    || rustup target add wasm32-unknown-unknown
bindgen=$(scripts/wasm-bindgen-cli.sh)

# The js profile (Cargo.toml): the physics at full speed, the rest for size, linked whole.
cargo build --profile js --target wasm32-unknown-unknown -p carom-js
rm -rf "$out"
mkdir -p "$out"
# Function names only name frames in stack traces; the package's errors carry messages.
"$bindgen" --target web --remove-name-section --out-dir "$out" \
    "$target_dir/wasm32-unknown-unknown/js/carom_js.wasm"
cp crates/carom-js/package/* "$out/"
cp LICENSE-MIT LICENSE-APACHE "$out/"

tarball=$(cd "$out" && npm pack --pack-destination .. --loglevel=error)
wasm="$out/carom_js_bg.wasm"
kib() { echo "$(( ($1 + 512) / 1024 )) KiB"; }
echo "built $out and $(dirname "$out")/$tarball"
echo "module: $(kib "$(stat -c %s "$wasm")"), $(kib "$(gzip -9c "$wasm" | wc -c)") gzipped;" \
    "package: $(kib "$(stat -c %s "$(dirname "$out")/$tarball")") packed"
