#!/usr/bin/env bash
# Runs every cargo-fuzz target for SECONDS seconds each, one after the other, and fails on
# the first crash. Usage: fuzz/run.sh SECONDS [TARGET...]
#
# Installs cargo-fuzz if it is missing and uses the first nightly toolchain rustup has
# (installing one if there is none).
# Inputs that once found a bug live in fuzz/regressions/TARGET/ and are replayed first (as
# a read-only corpus); new corpus entries go to fuzz/corpus/TARGET/ (not committed), crash
# inputs to fuzz/artifacts/TARGET/.
#
# Builds without a sanitizer (`-s none`): the crate's `unsafe` is unchecked chunk access
# (src/simd/ and the engine's scratch rows in src/forces/engine/), whose `debug_assert!`
# bounds checks the debug assertions (`-a`, which also turn on overflow checks) keep on,
# and intrinsics, so AddressSanitizer would mostly slow the search down. Optimisations
# (`-O`) are on.
set -euo pipefail

seconds=${1:?usage: fuzz/run.sh SECONDS [TARGET...]}
shift
cd "$(dirname "$0")/.."

toolchain=$(rustup toolchain list | awk '/^nightly/ { print $1; exit }')
if [[ -z "$toolchain" ]]; then
    echo "fuzz/run.sh: no nightly toolchain; installing one" >&2
    rustup toolchain install nightly --profile minimal
    toolchain=nightly
fi
if ! cargo "+$toolchain" fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz --locked
fi

# FUZZ_SANITIZER=address runs the targets under AddressSanitizer instead.
flags=(-s "${FUZZ_SANITIZER:-none}" -a -O)
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
    mapfile -t targets < <(cargo "+$toolchain" fuzz list)
fi
cargo "+$toolchain" fuzz build "${flags[@]}"

for target in "${targets[@]}"; do
    mkdir -p "fuzz/corpus/$target" "fuzz/regressions/$target"
    echo "== fuzz $target for ${seconds}s"
    # -timeout: an input running longer than 20 s is a hang, reported like a crash.
    cargo "+$toolchain" fuzz run "${flags[@]}" "$target" \
        "fuzz/corpus/$target" "fuzz/regressions/$target" -- \
        -max_total_time="$seconds" -timeout=20 -print_final_stats=1
done
echo "fuzz/run.sh: ${#targets[@]} target(s), no crash"
