#!/usr/bin/env bash
# The same bits on every architecture, end to end: the command line built for several
# targets runs the same simulations, and every CSV must be byte-identical to the first
# build's. Each argument is LEVEL=COMMAND: the command that runs that build of
# `springwater` (with its emulator, if any), and the SIMD level its `simulate` summary must
# name (`any` to accept the CPU's choice). For example:
#
#   cli/tests/same_csv.sh \
#     any=target/release/springwater \
#     neon="qemu-aarch64 -L /usr/aarch64-linux-gnu target/cross/aarch64-unknown-linux-gnu/release/springwater" \
#     portable="node --no-warnings --single-threaded .ci/wasi-run.mjs target/cross/wasm32-wasip1/release/springwater.wasm"
#
# The scenarios: a pinned pool with drops, a free edge, and open water (an absorbing
# frame) with two floaters, on the threads each target has (all cores natively, one on
# wasm32). Then each build runs `bench` on a tiny grid, whose first line must name the
# same level (`bench simd=LEVEL `). Exits 1 on the first difference, naming the build and
# the scenario.
set -euo pipefail

if [ $# -lt 2 ]; then
  echo "usage: $0 LEVEL=COMMAND LEVEL=COMMAND [...]   (the first is the reference)" >&2
  exit 2
fi

scenarios=(
  "pinned|--size 96x64 --steps 120 --drop 30,20,2,5 --drop 70,40,-1.5,3"
  "free|--size 80x80 --steps 150 --boundary free --drop 10,10,3,6"
  "open-water|--size 128x96 --steps 200 --boundary absorbing --drop 64,48,2,4 --floater 60,40,3,1.5 --floater 70,55,1,0.8"
)

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

build=0
for arg in "$@"; do
  level=${arg%%=*}
  command=${arg#*=}
  for scenario in "${scenarios[@]}"; do
    name=${scenario%%|*}
    flags=${scenario#*|}
    csv="$work/$build-$name.csv"
    # shellcheck disable=SC2086  # the command is words: an emulator, its flags, the program
    summary=$($command simulate $flags --csv "$csv" 2>&1) || {
      echo "$level ($command): simulate $flags failed:"
      echo "$summary"
      exit 1
    }
    simd=$(grep -E '^simd ' <<<"$summary" || true)
    if [ "$level" != any ] && ! grep -qE "^simd +$level " <<<"$summary"; then
      echo "$level ($command), $name: the summary names another level: $simd"
      exit 1
    fi
    digest=$(sha256sum "$csv" | cut -c1-16)
    printf '%-10s %-11s %s  %s\n' "$level" "$name" "$digest" "${simd#simd }"
    if [ "$build" -gt 0 ] && ! cmp -s "$work/0-$name.csv" "$csv"; then
      echo "$level ($command), $name: the CSV differs from the first build's"
      cmp "$work/0-$name.csv" "$csv" | head -1 || true
      exit 1
    fi
  done
  # bench's first line names the level that ran (a few steps on a tiny grid: under an
  # emulator its times mean nothing, the line is what is checked).
  # shellcheck disable=SC2086
  report=$($command bench --size 24x16 --steps 4 --repeats 1 --compare none 2>"$work/err") || {
    echo "$level ($command): bench failed:"
    cat "$work/err"
    exit 1
  }
  first=$(head -1 <<<"$report")
  if [ "$level" != any ] && [[ "$first" != "bench simd=$level "* ]]; then
    echo "$level ($command): bench's first line names another level: $first"
    exit 1
  fi
  printf '%-10s %-11s %s\n' "$level" bench "${first%% (*}"
  build=$((build + 1))
done
echo "same CSVs from all $build builds (${#scenarios[@]} scenarios each); bench names each level"
