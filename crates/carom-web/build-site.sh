#!/usr/bin/env bash
# Builds the carom demo as a static web site in one folder (default target/web): index.html,
# the demo compiled to WebAssembly and its JavaScript glue. Any static server serves it, e.g.
#   python3 -m http.server -d target/web 8000    and open http://127.0.0.1:8000
# It adds the wasm32 target with rustup and installs the wasm-bindgen command line the
# version Cargo.lock names (scripts/wasm-bindgen-cli.sh) when they are missing.
set -euo pipefail
cd "$(dirname "$0")/../.."
out="${1:-target/web}"
target_dir="${CARGO_TARGET_DIR:-target}"

rustup target list --installed | grep -qx wasm32-unknown-unknown \
    || rustup target add wasm32-unknown-unknown

# wasm-bindgen's command line, the version of the crate built in.
bindgen=$(scripts/wasm-bindgen-cli.sh)

cargo build --profile web --target wasm32-unknown-unknown -p carom-web
rm -rf "$out"
mkdir -p "$out"
# The function names (a sixth of the module) only name frames in a browser's stack traces;
# a panic's message reaches the page without them.
"$bindgen" --target web --no-typescript --remove-name-section --out-dir "$out" \
    "$target_dir/wasm32-unknown-unknown/web/carom_web.wasm"
cp crates/carom-web/index.html "$out/"
echo "built $out: serve it with any static server, for example"
echo "  python3 -m http.server -d $out 8000    and open http://127.0.0.1:8000"
