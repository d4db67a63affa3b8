#!/usr/bin/env bash
# A soak test (not a CI step): two runs of examples/soak.rs side by side, open water in
# the rain with a window that follows a moving point and 200 floating bodies, for the same
# fixed number of steps. Usage: scripts/soak.sh STEPS [OUT_DIR]   (OUT_DIR: soak-out)
#
# Checks that
#   * every step succeeds and the state stays finite (the example checks every 10,000
#     steps and at the end, and exits 1 on a failed step);
#   * memory stays flat: each run's resident set (VmRSS from /proc) is sampled every 30 s
#     into OUT_DIR/rss.log;
#   * the two runs end with the same state hash.
# Run it under `nice -n 19` on a shared machine; the step count that takes an hour depends
# on the machine and its load (360,000 took about an hour on 2 shared cores, see
# docs/reliability.md).
set -euo pipefail

steps=${1:?usage: scripts/soak.sh STEPS [OUT_DIR]}
out=${2:-soak-out}
cd "$(dirname "$0")/.."

cargo build --release --example soak
bin="${CARGO_TARGET_DIR:-target}/release/examples/soak"
mkdir -p "$out"

"$bin" "$steps" 10000 >"$out/run1.log" 2>&1 &
first=$!
"$bin" "$steps" 10000 >"$out/run2.log" 2>&1 &
second=$!

rss() { awk '/^VmRSS/ { print $2 }' "/proc/$1/status" 2>/dev/null || echo -; }
echo "seconds run1_rss_kib run2_rss_kib" >"$out/rss.log"
start=$SECONDS
while kill -0 "$first" 2>/dev/null || kill -0 "$second" 2>/dev/null; do
    echo "$((SECONDS - start)) $(rss "$first") $(rss "$second")" >>"$out/rss.log"
    sleep 30
done

status=0
wait "$first" || status=$?
wait "$second" || status=$?
if [[ $status -ne 0 ]]; then
    echo "soak: a run failed (see $out/run1.log, $out/run2.log)" >&2
    exit 1
fi

# The resident set after the first ten minutes (construction and the first shifts done):
# its smallest and largest sample per run.
awk 'NR > 1 && $1 >= 600 && $2 != "-" { a = $2; if (!lo1 || a < lo1) lo1 = a; if (a > hi1) hi1 = a }
     NR > 1 && $1 >= 600 && $3 != "-" { b = $3; if (!lo2 || b < lo2) lo2 = b; if (b > hi2) hi2 = b }
     END { printf "rss after 600 s: run1 %s..%s KiB, run2 %s..%s KiB\n", lo1, hi1, lo2, hi2 }' \
    "$out/rss.log"

one=$(grep '^final' "$out/run1.log")
two=$(grep '^final' "$out/run2.log")
echo "run1: $one"
echo "run2: $two"
if [[ "$one" != "$two" ]]; then
    echo "soak: the two runs end with different hashes" >&2
    exit 1
fi
echo "soak: $steps steps, both runs finite, the same hash, $((SECONDS - start)) s"
