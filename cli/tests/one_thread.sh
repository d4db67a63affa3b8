#!/usr/bin/env bash
# The command line on a target without threads (wasm32-wasip1 without the atomics feature):
# `--threads 1` runs on the one thread there is, and `--threads 2` is refused with one line
# that names the target. Each argument is TARGET=COMMAND: the command that runs that build
# of `springwater` (with its runtime) and the word its error must name. For example:
#
#   cli/tests/one_thread.sh \
#     wasm32="node --no-warnings --single-threaded .ci/wasi-run.mjs target/cross/wasm32-wasip1/release/springwater.wasm"
#
# For each build: `simulate --threads 1` succeeds and writes the CSV the same run writes
# without the flag; `bench --threads 1` succeeds and reports one thread; `simulate
# --threads 2` exits non-zero, writes nothing to standard output and exactly one line to
# standard error, an error naming `--threads 2` and the target. Exits 1 on the first
# failure, naming the build and the check.
set -euo pipefail

if [ $# -lt 1 ]; then
  echo "usage: $0 TARGET=COMMAND [...]" >&2
  exit 2
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
flags="--size 40x32 --steps 30 --drop 20,16,1,4"

fail() {
  echo "$target ($command): $*"
  exit 1
}

for arg in "$@"; do
  target=${arg%%=*}
  command=${arg#*=}

  # shellcheck disable=SC2086  # the command is words: a runtime, its flags, the program
  $command simulate $flags --csv "$work/default.csv" >"$work/out" 2>"$work/err" \
    || fail "simulate without --threads failed: $(cat "$work/err")"
  # shellcheck disable=SC2086
  $command simulate $flags --threads 1 --csv "$work/one.csv" >"$work/out" 2>"$work/err" \
    || fail "simulate --threads 1 failed: $(cat "$work/err")"
  cmp -s "$work/default.csv" "$work/one.csv" \
    || fail "simulate --threads 1 wrote another CSV than without the flag"
  # shellcheck disable=SC2086
  $command bench --size 24x16 --steps 4 --repeats 1 --compare none --threads 1 \
    >"$work/out" 2>"$work/err" || fail "bench --threads 1 failed: $(cat "$work/err")"
  grep -q ' 1 thread(s)$' <(head -1 "$work/out") \
    || fail "bench --threads 1 reports other threads: $(head -1 "$work/out")"
  echo "$target: --threads 1 runs simulate (the same CSV as without the flag) and bench"

  status=0
  # shellcheck disable=SC2086
  $command simulate $flags --threads 2 >"$work/out" 2>"$work/err" || status=$?
  [ "$status" -ne 0 ] || fail "simulate --threads 2 succeeded"
  [ ! -s "$work/out" ] || fail "simulate --threads 2 wrote to standard output: $(cat "$work/out")"
  lines=$(wc -l <"$work/err")
  error=$(cat "$work/err")
  [ "$lines" -eq 1 ] || fail "simulate --threads 2: $lines lines on standard error, not one:
$error"
  [[ "$error" == "springwater: error: --threads 2"* ]] \
    || fail "simulate --threads 2: not an error about the flag: $error"
  [[ "$error" == *"$target"* ]] || fail "simulate --threads 2: the error does not name $target: $error"
  echo "$target: --threads 2 refused (exit $status): $error"
done
echo "one thread: all $# builds"
