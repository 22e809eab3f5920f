#!/usr/bin/env bash
# What each effect costs per step, in instructions (deterministic, unlike wall time on a shared
# machine): for each effect set, callgrind counts a 100-step and a 300-step run of a scene and
# the difference divided by 200 is the cost of one step. Prints the table as CSV; run through
# `carom-bench measure`, which writes it to docs/effects/effect-cost.csv under the lines naming
# the machine and the date, for `carom-bench docs` to draw docs/effects.md's table. Needs
# valgrind.
#
#   cargo run --release -p carom-bench -- measure docs/effects/effect-cost.csv -- \
#       scripts/effect_cost.sh [demos/pyramid.ron]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-demos/pyramid.ron}
cargo build -q --release -p carom-demo >&2
count() {
    valgrind --tool=callgrind --callgrind-out-file=/dev/null \
        ./target/release/carom run "$scene" --steps "$1" --json --effects="$2" 2>&1 >/dev/null |
        grep -oE 'Collected : [0-9]+' | grep -oE '[0-9]+'
}
configs=(
    "-sleeping"
    "-sleeping,-gravity"
    "-sleeping,-drag"
    "-sleeping,-friction"
    "-sleeping,-restitution"
    "-sleeping,-continuous"
    "+sleeping"
    "-gravity,-drag,-friction,-restitution,-continuous,-sleeping"
)
printf 'effects,instructions_per_step\n'
for config in "${configs[@]}"; do
    a=$(count 100 "$config")
    b=$(count 300 "$config")
    printf '"%s",%d\n' "$config" $(((b - a) / 200))
done
