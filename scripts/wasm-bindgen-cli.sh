#!/usr/bin/env bash
# Prints the path of a wasm-bindgen command line of the exact version Cargo.lock names (it must
# match the wasm-bindgen crate built in), installing it through cargo into
# $CARGO_TARGET_DIR/tools (default target/tools) when it is missing. Used by the web site's and
# the npm package's builds.
set -euo pipefail
cd "$(dirname "$0")/.."
target_dir="${CARGO_TARGET_DIR:-target}"
version=$(awk '$0 == "name = \"wasm-bindgen\"" { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
bindgen="$target_dir/tools/bin/wasm-bindgen"
if [ "$("$bindgen" --version 2>/dev/null)" != "wasm-bindgen $version" ]; then
    echo "installing wasm-bindgen-cli $version into $target_dir/tools" >&2
    # A tool that runs for seconds: unoptimised, it installs in a third of the time and runs
    # a few seconds longer, with the same output. Its default feature is TLS for the test
    # runner's downloads, which the builds never make.
    CARGO_PROFILE_RELEASE_OPT_LEVEL=0 CARGO_PROFILE_RELEASE_DEBUG=false \
        cargo install wasm-bindgen-cli --version "$version" --no-default-features \
        --root "$target_dir/tools" >&2
fi
echo "$bindgen"
