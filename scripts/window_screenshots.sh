#!/usr/bin/env bash
# Drives the real demo window under Xvfb: grabs the box of the grabbing scene, swings it up and
# throws it, and saves the window while held (docs/images/window.png) and the throw as a strip
# of three moments (docs/images/throw.png), and the smash gone back in time
# (docs/images/timeline.png). Needs xvfb, xdotool, x11-apps and netpbm (Debian).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p carom-demo
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp/carom-runtime}"
mkdir -p -m 700 "$XDG_RUNTIME_DIR"
unset WAYLAND_DISPLAY
export DISPLAY=:97
work=$(mktemp -d)
Xvfb "$DISPLAY" -screen 0 1280x720x24 >"$work/xvfb.log" 2>&1 &
xvfb=$!
trap 'kill "$carom" "$xvfb" 2>/dev/null || true; rm -rf "$work"' EXIT
sleep 1
target/release/carom --scene demos/grabbing.ron --size 1280x720 >"$work/carom.log" 2>&1 &
carom=$!
sleep 4

shot() { xwd -root -silent | xwdtopnm 2>/dev/null >"$work/$1.pnm"; }
# The window fills the screen: a 300 px sidebar, then the scene, 980 x 720, whose 1280 x 720
# framing is scaled by 980/1280 to fit. The grabbing scene looks at (0, 5) at 60 px/m there,
# so the box resting at (-3, 0.6) is at about (652, 563).
xdotool mousemove 652 563
sleep 0.3
xdotool mousedown 1
sleep 0.3
for i in $(seq 1 12); do
    xdotool mousemove $((652 + i * 12)) $((563 - i * 18))
    sleep 0.05
done
shot held
for i in $(seq 1 8); do
    xdotool mousemove $((796 - i * 35)) $((347 - i * 12))
    sleep 0.03
done
xdotool mouseup 1
sleep 0.25
shot thrown
sleep 1.5
shot landed

pnmtopng "$work/held.pnm" >docs/images/window.png
for moment in held thrown landed; do
    pnmcut -left 380 -top 100 -width 820 -height 560 "$work/$moment.pnm" |
        pnmscale 0.5 >"$work/$moment.small.pnm"
done
pnmcat -lr "$work/held.small.pnm" "$work/thrown.small.pnm" "$work/landed.small.pnm" |
    pnmtopng >docs/images/throw.png
# The timeline: the smash played 320 steps, then taken back to step 150 through the window's
# script (what the sidebar's scrubber does).
target/release/carom --scene demos/smash.ron --size 1280x720 --steps-per-frame 4 --frames 92 \
    --at 81:pause --at 81:go-to=150 --screenshot docs/images/timeline.png >"$work/timeline.log"
echo "wrote docs/images/window.png, docs/images/throw.png and docs/images/timeline.png"
