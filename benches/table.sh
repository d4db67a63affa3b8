#!/usr/bin/env bash
# Builds the default and the `-C target-cpu=native` binaries and prints the performance
# table of docs/performance.md: `springwater bench` at 64², 256², 1024², 2048² on 1 and 2 threads.
# The default build dispatches at run time to the widest SIMD level the CPU has;
# `default:sse2` forces a level through SPRINGWATER_SIMD. The simd column is the level
# that ran (bench's first line). Every ratio in a row comes from one run (the kernels are
# interleaved, medians of --repeats rounds).
# Usage: [BUILDS="default:sse2 default native"] [SIZES="256 2048"] benches/table.sh [REPEATS]
set -euo pipefail
cd "$(dirname "$0")/.."
repeats="${1:-5}"
cargo build --release --quiet
RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR=target/native cargo build --release --quiet
echo "| build | simd | grid | threads | engine node updates/s | × single steps | × scalar reference | × naive AoS | × memory floor |"
echo "|---|---|---|---|---|---|---|---|---|"
for spec in ${BUILDS:-default:sse2 default native}; do
  build=${spec%%:*}
  level=${spec#*:}
  [ "$level" = "$spec" ] && level=""
  case "$build" in
    default) bin=target/release/springwater ;;
    native) bin=target/native/release/springwater ;;
    *) echo "unknown build $build" >&2; exit 2 ;;
  esac
  for n in ${SIZES:-64 256 1024 2048}; do
    steps=$(( n <= 256 ? 200 : (n == 1024 ? 24 : 16) ))
    for threads in 1 2; do
      if [ -n "$level" ]; then
        out=$(SPRINGWATER_SIMD=$level "$bin" bench --size "${n}x${n}" --steps "$steps" --repeats "$repeats" --threads "$threads")
      else
        out=$("$bin" bench --size "${n}x${n}" --steps "$steps" --repeats "$repeats" --threads "$threads")
      fi
      simd=$(echo "$out" | head -1 | sed -n 's/^bench simd=\([a-z0-9]*\).*/\1/p')
      rate=$(echo "$out" | awk '$1 == "engine" {print $3}')
      ratio() { echo "$out" | awk -v k="$1" '$1 == k {print $4}'; }
      # The table prints engine speed over each kernel: kernel time / engine time.
      echo "| $build | $simd | ${n}² | $threads | $rate | $(ratio engine-1step) | $(ratio reference) | $(ratio naive) | $(ratio memory-floor) |"
    done
  done
done
