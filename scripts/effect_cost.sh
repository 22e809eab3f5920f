#!/usr/bin/env bash
# What each effect costs per step, in instructions (deterministic, unlike wall time on a shared
# machine): for each effect set, callgrind counts a 100-step and a 300-step run of a scene and
# the difference divided by 200 is the cost of one step. Writes docs/effects/effect-cost.csv,
# from which `carom-bench docs` draws docs/effects.md's table. Needs valgrind.
#
#   scripts/effect_cost.sh [demos/pyramid.ron]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-demos/pyramid.ron}
out=docs/effects/effect-cost.csv
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
cpu=$(sed -n 's/^model name[[:space:]]*: *//p' /proc/cpuinfo | head -n1)
mkdir -p "$(dirname "$out")"
{
    printf '# measured: %s\n# machine: %s\n# cores: %s\n' "$(date -u +%F)" "${cpu:-$(uname -m)}" "$(nproc)"
    printf '# command: scripts/effect_cost.sh %s\n# runs: 1\n' "$scene"
    printf 'effects,instructions_per_step\n'
    for config in "${configs[@]}"; do
        a=$(count 100 "$config")
        b=$(count 300 "$config")
        printf '"%s",%d\n' "$config" $(((b - a) / 200))
    done
} >"$out.new"
mv "$out.new" "$out"
cat "$out"
