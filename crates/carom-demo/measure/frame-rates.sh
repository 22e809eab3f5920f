#!/usr/bin/env bash
# The window's frame rates under Xvfb on Mesa's lavapipe, as the CSV table docs/rendering.md
# draws: `carom-bench measure docs/rendering/frame-rates.csv -- crates/carom-demo/measure/frame-rates.sh`.
# Each row is one run of `carom --scene demos/NAME.ron --frames N` in a 1280x720 screen; its
# report (median frame, frames a second, median step, bodies, steps, all over the run) goes to
# standard error and its figures to the table on standard output. Build the binary first:
# `cargo build --release -p carom-demo`. Needs xvfb (xvfb-run) and Mesa's Vulkan drivers.
set -euo pipefail
cd "$(dirname "$0")/../../.."
carom=${CAROM:-target/release/carom}
if [[ ! -x $carom ]]; then
    echo "no $carom: build it with cargo build --release -p carom-demo" >&2
    exit 1
fi
# The table says lavapipe: Vulkan, whatever else the machine offers.
export WGPU_BACKEND=vulkan
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp/carom-runtime}"
mkdir -p -m 700 "$XDG_RUNTIME_DIR"
unset WAYLAND_DISPLAY

# row LABEL SCENE FRAMES: runs the window and prints the row.
row() {
    local label=$1 scene=$2 frames=$3 report
    report=$(xvfb-run -a -s "-screen 0 1280x720x24" \
        "$carom" --scene "demos/$scene.ron" --frames "$frames" | tail -n 1)
    echo "$report" >&2
    # demos/NAME.ron: F frames at WxH on ADAPTER: median frame A ms (B frames/s),
    # median step C ms, D bodies, E steps
    local pattern='median frame ([0-9.]+) ms \(([0-9.]+) frames/s\), median step ([0-9.]+) ms, ([0-9]+) bodies, ([0-9]+) steps'
    if [[ ! $report =~ $pattern ]]; then
        echo "cannot read the window's report: $report" >&2
        exit 1
    fi
    local m=("${BASH_REMATCH[@]}")
    echo "\"$label\",${m[4]},${m[1]} ms,${m[2]},${m[3]} ms,${m[5]}"
}

echo "scene,bodies,median frame,frames/s,median step,steps"
row '`grabbing`' grabbing 600
row '`mixed_1000`, first 150 frames' mixed_1000 150
row '`mixed_1000`, 600 frames' mixed_1000 600
