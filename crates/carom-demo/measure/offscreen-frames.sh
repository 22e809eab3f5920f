#!/usr/bin/env bash
# Offscreen frame times of `large_pyramid` at 1280x720 on Mesa's software drivers, as the CSV
# table docs/rendering.md draws:
# `carom-bench measure --runs 3 docs/rendering/offscreen-frames.csv -- crates/carom-demo/measure/offscreen-frames.sh 3`.
# Each backend runs `carom snapshot demos/large_pyramid.ron --steps 1 --time-frames 20` RUNS
# times (default 3); a cell is the median of the runs' medians, and the fastest and slowest
# run. Reports go to standard error, the table to standard output. Build the binary first:
# `cargo build --release -p carom-demo`.
set -euo pipefail
cd "$(dirname "$0")/../../.."
carom=${CAROM:-target/release/carom}
runs=${1:-3}
if [[ ! -x $carom ]]; then
    echo "no $carom: build it with cargo build --release -p carom-demo" >&2
    exit 1
fi
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp/carom-runtime}"
mkdir -p -m 700 "$XDG_RUNTIME_DIR"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# cell DECIMALS VALUES...: the median, and (fastest-slowest) when there are several.
cell() {
    local decimals=$1
    shift
    printf '%s\n' "$@" | sort -g | awk -v d="$decimals" '
        { v[NR] = $1 }
        END {
            fmt = "%." d "f"
            out = sprintf(fmt " ms", v[int((NR + 1) / 2)])
            if (NR > 1) out = out sprintf(" (" fmt "-" fmt ")", v[1], v[NR])
            print out
        }'
}

echo "backend,adapter,render and read back,describe the world"
for backend in vulkan gl; do
    render=() describe=() adapter=
    for _ in $(seq "$runs"); do
        report=$(WGPU_BACKEND=$backend "$carom" snapshot demos/large_pyramid.ron --steps 1 \
            --out "$work/p.png" --time-frames 20)
        echo "$report" >&2
        # demos/large_pyramid.ron: 1 steps, N bodies, WxH on ADAPTER -> FILE
        # frame     A ms describe + B ms render and read back (medians of 20 frames)
        if [[ ! $report =~ \ on\ (.*)\ -\>\ .*frame\ +([0-9.]+)\ ms\ describe\ \+\ ([0-9.]+)\ ms\ render ]]; then
            echo "cannot read the snapshot's report" >&2
            exit 1
        fi
        adapter=${BASH_REMATCH[1]}
        describe+=("${BASH_REMATCH[2]}")
        render+=("${BASH_REMATCH[3]}")
    done
    echo "\`$backend\`,\"$adapter\",$(cell 1 "${render[@]}"),$(cell 2 "${describe[@]}")"
done
