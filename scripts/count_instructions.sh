#!/usr/bin/env bash
# Instructions per node update of the engine's step, counted rather than timed (a count
# does not move with the machine's load): x86-64 instructions under valgrind's cachegrind
# at each level valgrind runs, and wasm operators under wasmtime's fuel meter for the
# portable and the +simd128 builds for wasm32-wasip1. The counts of docs/performance.md.
#
#   scripts/count_instructions.sh [x86|wasm|all]     (default all)
#   X86_LEVELS="scalar portable sse2 avx2" X86_SIZES=256x256 scripts/count_instructions.sh x86
#
# Each figure is `springwater bench --threads 1 --compare none --repeats R` run for LONG
# steps minus the same for SHORT steps (the set-up, the drop and the first pass cancel),
# divided by the node updates between the two. The bench runs a warm-up round and then R
# rounds, each of the given steps, so the two runs differ by (R + 1) x (LONG - SHORT)
# steps: x86 300 and 100 steps with R = 1 (400 steps), wasm 60 and 20 with R = 5 (240).
#
# The x86 figures docs/performance.md gave before 2026-11-28 were divided by 200 steps,
# not 400: they are instructions per two node updates. This script prints both: the true
# count per node update, and the earlier column (twice it) to compare with the old
# tables. The wasm figures were always divided by all 240 steps.
#
# Needs valgrind, the wasm32-wasip1 target (rustup target add wasm32-wasip1) and the
# `wasmtime` package from PyPI (pip install wasmtime; scripts/wasm_fuel.py). valgrind has
# no AVX-512: asked for avx512, the binary runs AVX2 (the bench's first line names the
# level that ran; this script prints it). The default build goes to $CARGO_TARGET_DIR
# (default target/); the +simd128 one, with other RUSTFLAGS, to its simd128/ below it.
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-all}
target=${CARGO_TARGET_DIR:-target}

X86_LEVELS=${X86_LEVELS:-"portable sse2 avx2"}
X86_SIZES=${X86_SIZES:-"256x256 2048x32"}
X86_LONG=300 X86_SHORT=100 X86_REPEATS=1
WASM_SIZES=${WASM_SIZES:-"256x256"}
WASM_LONG=60 WASM_SHORT=20 WASM_REPEATS=5
log=$(mktemp)
trap 'rm -f "$log"' EXIT

nodes() { echo $((${1%x*} * ${1#*x})); }

# Instructions of one bench run under cachegrind (its "I refs" line); the level that ran
# goes to $log.
x86_run() { # level size steps
    SPRINGWATER_SIMD=$1 valgrind --tool=cachegrind --cache-sim=no \
        --cachegrind-out-file=/dev/null "$target/release/springwater" bench \
        --size "$2" --steps "$3" --threads 1 --compare none --repeats $X86_REPEATS \
        >"$log" 2>&1
    awk '/I *refs:/ { gsub(",", "", $NF); print $NF }' "$log"
}

wasm_run() { # wasm size steps
    python3 scripts/wasm_fuel.py "$1" bench --size "$2" --steps "$3" --threads 1 \
        --compare none --repeats $WASM_REPEATS 2>"$log" | awk '/^fuel/ { print $2 }'
}

ran() { grep -o 'bench simd=[a-z0-9]*' "$log" | cut -d= -f2; }

# (long - short) / (steps x nodes), two decimals.
per_node() { # long short steps size
    python3 -c "print(f'{($1 - $2) / ($3 * $(nodes "$4")):.2f}')"
}

echo "| target | level asked | ran | grid | per node update | as counted before | long run | short run |"
echo "|---|---|---|---|---|---|---|---|"
if [[ $what == x86 || $what == all ]]; then
    cargo build --release -p springwater-cli --quiet
    steps=$(((X86_REPEATS + 1) * (X86_LONG - X86_SHORT)))
    for size in $X86_SIZES; do
        for level in $X86_LEVELS; do
            long=$(x86_run "$level" "$size" $X86_LONG)
            short=$(x86_run "$level" "$size" $X86_SHORT)
            echo "| x86-64 | $level | $(ran) | $size | $(per_node "$long" "$short" $steps "$size") |" \
                "$(per_node "$long" "$short" $((X86_LONG - X86_SHORT)) "$size") | $long | $short |"
        done
    done
fi
if [[ $what == wasm || $what == all ]]; then
    cargo build --release -p springwater-cli --quiet --target wasm32-wasip1
    RUSTFLAGS="-C target-feature=+simd128" CARGO_TARGET_DIR="$target/simd128" \
        cargo build --release -p springwater-cli --quiet --target wasm32-wasip1
    steps=$(((WASM_REPEATS + 1) * (WASM_LONG - WASM_SHORT)))
    for size in $WASM_SIZES; do
        for build in portable simd128; do
            wasm=$target/wasm32-wasip1/release/springwater.wasm
            [[ $build == simd128 ]] && wasm=$target/simd128/wasm32-wasip1/release/springwater.wasm
            long=$(wasm_run "$wasm" "$size" $WASM_LONG)
            short=$(wasm_run "$wasm" "$size" $WASM_SHORT)
            count=$(per_node "$long" "$short" $steps "$size")
            echo "| wasm32 | $build | $(ran) | $size | $count | $count | $long | $short |"
        done
    done
fi
