"""WebAssembly operators per node update of the npm package's modules, counted with
wasmtime's fuel meter (each operator costs one unit; load-independent, unlike a timing).

    pip install wasmtime
    python3 scripts/package_fuel.py web/wasm/springwater-simd128.wasm [size]

Makes a size x size surface (256 by default) through the C ABI, drops water at its centre
(height 1, radius 4 cells, as web/test/rate.mjs and `springwater bench` do), steps 20
steps, then prints the operators per node update of `sw_surface_step(60)` minus
`sw_surface_step(20)` over 40 steps (passes of 4 steps) and of one `sw_surface_step(1)`.
"""

import struct
import sys

import wasmtime as wt

PARAMS_SIZE = 60  # sizeof(SwParams) on wasm32; cols at 4, rows at 8


def main():
    path = sys.argv[1]
    size = int(sys.argv[2]) if len(sys.argv) > 2 else 256
    config = wt.Config()
    config.consume_fuel = True
    engine = wt.Engine(config)
    store = wt.Store(engine)
    store.set_fuel(10**15)
    store.set_wasi(wt.WasiConfig())
    linker = wt.Linker(engine)
    linker.define_wasi()
    ex = linker.instantiate(store, wt.Module.from_file(engine, path)).exports(store)
    memory = ex["memory"]

    def u32(at, value=None):
        if value is None:
            return struct.unpack("<I", memory.read(store, at, at + 4))[0]
        memory.write(store, struct.pack("<I", value), at)
        return value

    p = ex["sw_wasm_alloc"](store, 256)
    ex["sw_params_default"](store, p)  # a struct return: its address comes first
    u32(p + 4, size)
    u32(p + 8, size)
    assert ex["sw_surface_create"](store, p, p + PARAMS_SIZE) == 0
    surface = u32(p + PARAMS_SIZE)
    assert ex["sw_surface_drop_at"](store, surface, size / 2, size / 2, 1.0, 4.0) == 0

    def fuel(steps):
        before = store.get_fuel()
        assert ex["sw_surface_step"](store, surface, steps) == 0
        return before - store.get_fuel()

    fuel(20)
    short, long = fuel(20), fuel(60)
    nodes = size * size
    print(f"{path}: {(long - short) / 40 / nodes:.1f} operators per node update "
          f"({size}x{size}, passes of 4); one step(1): {fuel(1) / nodes:.1f}")


if __name__ == "__main__":
    main()
