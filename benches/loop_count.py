#!/usr/bin/env python3
"""Instructions per node of the step's inner loop, where the step cannot be timed.

Runs `springwater simulate --size 128x64 --steps 4 --threads 1` under qemu-user with one
instruction per translation block and every executed block logged, counts how often each
instruction ran, and keeps those that ran exactly as often as the row kernel's loop of two
8-lane chunks iterates (63 rows with a row below x 4 steps x 7 pairs = 1764 times: the
pairs loop of `RowKernel::run_into`), or a multiple of that within the loop's addresses.
Those are the loop body: the script prints its
length per node (16 nodes an iteration) and writes it, branches removed, for llvm-mca.

    benches/loop_count.py aarch64 target/aarch64-unknown-linux-gnu/release/springwater neon
    benches/loop_count.py aarch64 target/aarch64-unknown-linux-gnu/release/springwater portable
    benches/loop_count.py x86_64 target/release/springwater avx2
    llvm-mca-19 -mtriple=aarch64 -mcpu=neoverse-n1 -iterations=200 loop-neon.s

Needs qemu-user (7.2: `-singlestep`) and llvm-objdump. The log is about 1.5 GB while it
lives (in the system's temporary directory).
"""
import collections
import os
import re
import subprocess
import sys
import tempfile

ITERATIONS = 63 * 4 * 7
NODES_PER_ITERATION = 16


def main():
    arch, binary, level = sys.argv[1:4]
    qemu = {
        "aarch64": ["qemu-aarch64", "-L", "/usr/aarch64-linux-gnu"],
        "x86_64": ["qemu-x86_64", "-cpu", "max"],
    }[arch]
    with tempfile.TemporaryDirectory() as tmp:
        log = os.path.join(tmp, "exec.log")
        subprocess.run(
            qemu + ["-singlestep", "-d", "exec,nochain", "-D", log, binary, "simulate",
                    "--size", "128x64", "--steps", "4", "--threads", "1"],
            env=dict(os.environ, SPRINGWATER_SIMD=level), check=True,
            stdout=subprocess.DEVNULL)
        # "Trace 0: host [flags/guest pc/...]": count the guest program counters.
        runs = collections.Counter()
        with open(log) as f:
            for line in f:
                runs[int(line.split("[", 1)[1].split("/")[1], 16)] += 1
    body_pcs = sorted(pc for pc, n in runs.items() if n == ITERATIONS)
    if not body_pcs:
        sys.exit("no instruction ran as often as the loop iterates")
    # qemu-user loads a position-independent binary at a fixed base; the loop lies
    # within a few kilobytes, so the base is whatever makes its addresses the file's.
    base = {"aarch64": 0x5500000000, "x86_64": 0x4000000000}[arch]
    # The body's inner loops may lie just outside the instructions that run once an
    # iteration: look a page either side.
    lo, hi = body_pcs[0] - base - 4096, body_pcs[-1] - base + 4096
    dump = subprocess.run(
        ["llvm-objdump", "-d", "--no-show-raw-insn", f"--start-address={lo:#x}",
         f"--stop-address={hi:#x}", binary],
        check=True, capture_output=True, text=True).stdout
    comment = {"aarch64": "//", "x86_64": "#"}[arch]
    body = []
    for line in dump.splitlines():
        m = re.match(r"\s*([0-9a-f]+):\s+(.*)", line)
        n = runs.get(int(m.group(1), 16) + base, 0) if m else 0
        # An inner loop of the body (the portable level's per-axis loops) runs a
        # multiple of the iterations: its instructions count that many times.
        if n and n % ITERATIONS == 0:
            body += [m.group(2).split(comment)[0].strip()] * (n // ITERATIONS)
    branches = re.compile(r"^(b|bl|ret|cbn?z|tbn?z|j\w+|call)\b|^b\.")
    kept = [i for i in body if not branches.match(i.split()[0])]
    out = f"loop-{level}.s"
    with open(out, "w") as f:
        f.write("\n".join(kept) + "\n")
    ops = collections.Counter(i.split()[0] for i in body)
    print(f"{level}: {len(body)} instructions an iteration, "
          f"{len(body) / NODES_PER_ITERATION:.1f} per node; {out} (no branches)")
    print("  most frequent:", ", ".join(f"{op} {n}" for op, n in ops.most_common(12)))
    fused = [op for op in ops if re.match(r"f(n?m(la|ls|add|sub)|min|max)", op)]
    if fused:
        print("  fused multiply-adds or min/max in the loop:", fused)


if __name__ == "__main__":
    main()
