#!/usr/bin/env bash
# Regenerates the README's snapshots with `carom snapshot` (offscreen; Mesa's lavapipe or
# llvmpipe will do).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p carom-demo
carom=target/release/carom
$carom snapshot demos/pyramid.ron --steps 60 --size 960x540 --out docs/images/pyramid.png
$carom snapshot demos/collision.ron --steps 150 --size 960x540 --out docs/images/collision.png
$carom snapshot demos/normals.ron --steps 1 --size 960x540 --out docs/images/normals.png
$carom snapshot demos/bridge.ron --steps 150 --size 960x400 --out docs/images/bridge.png
$carom snapshot demos/ragdolls.ron --steps 85 --size 960x400 --out docs/images/ragdolls.png
