#!/usr/bin/env python3
"""Runs a wasm32-wasip1 program under wasmtime with fuel metering and prints the fuel it
consumed: one unit per wasm operator (wasmtime's costs: most operators 1, `nop`, `drop`,
`block`, `loop`, `end` and `else` 0), independent of the machine and its load.

    python3 scripts/wasm_fuel.py PROGRAM.wasm [ARGS...]

Needs the `wasmtime` package from PyPI (`pip install wasmtime`), which embeds the same
engine as the wasmtime CLI. The program's output goes to stderr; stdout gets one line,
`fuel N`. Used by scripts/count_instructions.sh."""

import sys

import wasmtime

FUEL = 1 << 62


def main() -> int:
    if len(sys.argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    path, args = sys.argv[1], sys.argv[2:]
    config = wasmtime.Config()
    config.consume_fuel = True
    engine = wasmtime.Engine(config)
    store = wasmtime.Store(engine)
    store.set_fuel(FUEL)
    wasi = wasmtime.WasiConfig()
    wasi.argv = [path] + args
    wasi.stdout_file = "/dev/stderr"
    wasi.inherit_stderr()
    store.set_wasi(wasi)
    linker = wasmtime.Linker(engine)
    linker.define_wasi()
    module = wasmtime.Module.from_file(engine, path)
    instance = linker.instantiate(store, module)
    start = instance.exports(store)["_start"]
    try:
        start(store)
    except wasmtime.ExitTrap as exit:
        if exit.code != 0:
            print(f"{path} exited with {exit.code}", file=sys.stderr)
            return 1
    print(f"fuel {FUEL - store.get_fuel()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
