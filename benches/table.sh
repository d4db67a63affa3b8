#!/usr/bin/env bash
# Builds the default (SSE2), the `-C target-cpu=x86-64-v3` (AVX2) and the
# `-C target-cpu=native` binaries and prints the README's performance table:
# `springwater bench` at 64², 256², 1024², 2048² on 1 and 2 threads.
# Every ratio in a row comes from one run (the kernels are interleaved, medians of
# --repeats rounds). Usage: [BUILDS="default x86-64-v3 native"] benches/table.sh [REPEATS]
set -euo pipefail
cd "$(dirname "$0")/.."
repeats="${1:-5}"
cargo build --release --quiet
RUSTFLAGS="-C target-cpu=x86-64-v3" CARGO_TARGET_DIR=target/v3 cargo build --release --quiet
RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR=target/native cargo build --release --quiet
echo "| build | grid | threads | engine node updates/s | × single steps | × scalar reference | × naive AoS | × memory floor |"
echo "|---|---|---|---|---|---|---|---|"
for build in ${BUILDS:-default x86-64-v3 native}; do
  case "$build" in
    default) bin=target/release/springwater ;;
    x86-64-v3) bin=target/v3/release/springwater ;;
    native) bin=target/native/release/springwater ;;
  esac
  for n in 64 256 1024 2048; do
    steps=$(( n <= 256 ? 200 : (n == 1024 ? 24 : 16) ))
    for threads in 1 2; do
      out=$("$bin" bench --size "${n}x${n}" --steps "$steps" --repeats "$repeats" --threads "$threads")
      rate=$(echo "$out" | awk '$1 == "engine" {print $3}')
      ratio() { echo "$out" | awk -v k="$1" '$1 == k {print $4}'; }
      # The table prints engine speed over each kernel: kernel time / engine time.
      echo "| $build | ${n}² | $threads | $rate | $(ratio engine-1step) | $(ratio reference) | $(ratio naive) | $(ratio memory-floor) |"
    done
  done
done
