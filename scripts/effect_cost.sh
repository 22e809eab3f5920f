#!/usr/bin/env bash
# What each effect costs per step, in instructions (deterministic, unlike wall time on a shared
# machine): for each effect set, callgrind counts a 100-step and a 300-step run of a scene and
# the difference divided by 200 is the cost of one step. Needs valgrind.
#
#   scripts/effect_cost.sh [demos/pyramid.ron]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-demos/pyramid.ron}
cargo build -q --release -p carom-demo
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
base=""
printf '| effects (from all six) | instructions/step | ratio |\n|---|---|---|\n'
for config in "${configs[@]}"; do
    a=$(count 100 "$config")
    b=$(count 300 "$config")
    per_step=$(((b - a) / 200))
    base=${base:-$per_step}
    ratio=$(awk -v a="$per_step" -v b="$base" 'BEGIN { printf "%.3f", a / b }')
    printf '| `%s` | %d | %s |\n' "$config" "$per_step" "$ratio"
done
