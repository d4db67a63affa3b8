"""Imports a springwater bake into Blender and checks vertex positions at one frame.

Run by cli/tests/bake_blender.rs:

    blender -b --python-exit-code 1 --python check_bake.py -- \
        (--glb FILE.glb | --obj FILE.obj --cache FILE.mdd|FILE.pc2) \
        --fps F --frame K --csv FILE.csv [--floater X,Y,Z]

The CSV is `springwater simulate --csv` after the same steps (col,row,x,y,z per node,
row-major). springwater is y-up, Blender z-up: both importers turn a point (x, y, z) into
(x, -z, y), so the check compares world positions against that. With `--floater` the
first floater's node (glb) is checked too: its position, and its orientation against the
rotation key the file holds for the frame.
"""
import argparse
import sys

import numpy

# Blender 3.4's glTF importer uses the alias numpy.bool, removed in numpy 1.24.
numpy.bool = bool

import bpy  # noqa: E402
import mathutils  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
ap = argparse.ArgumentParser()
ap.add_argument("--glb")
ap.add_argument("--obj")
ap.add_argument("--cache")
ap.add_argument("--fps", type=int, required=True)
ap.add_argument("--frame", type=int, required=True)
ap.add_argument("--csv", required=True)
ap.add_argument("--floater")
args = ap.parse_args(argv)



def rotation_key(path, name, key):
    """The rotation key `key` of node `name` in the .glb at `path`, [x, y, z, w]."""
    import json
    import struct

    data = open(path, "rb").read()
    (length,) = struct.unpack_from("<I", data, 12)
    doc = json.loads(data[20:20 + length])
    binary = 20 + length + 8
    node = [n["name"] for n in doc["nodes"]].index(name)
    animation = doc["animations"][0]
    channel = [c for c in animation["channels"]
               if c["target"] == {"node": node, "path": "rotation"}][0]
    accessor = doc["accessors"][animation["samplers"][channel["sampler"]]["output"]]
    view = doc["bufferViews"][accessor["bufferView"]]
    at = binary + view.get("byteOffset", 0) + accessor.get("byteOffset", 0) + 16 * key
    return list(struct.unpack_from("<4f", data, at))


bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
# The glTF importer turns a key at t seconds into frame t × fps: bake frame k at frame k.
scene.render.fps = args.fps

if args.glb:
    bpy.ops.import_scene.gltf(filepath=args.glb, import_shading="SMOOTH")
else:
    # The OBJ importer's defaults (-Z forward, Y up) keep the file's y-up coordinates in
    # the mesh and turn the object a quarter turn about x to stand z-up; the cache holds
    # the same y-up coordinates, so the modifier's axes stay the identity (its defaults).
    bpy.ops.wm.obj_import(filepath=args.obj, forward_axis="NEGATIVE_Z", up_axis="Y")
    water = [o for o in scene.objects if o.type == "MESH"][0]
    cache = water.modifiers.new("springwater", "MESH_CACHE")
    cache.cache_format = "MDD" if args.cache.lower().endswith(".mdd") else "PC2"
    cache.filepath = args.cache
    # The cache's first frame is bake frame 1.
    cache.frame_start = 1

water = [o for o in scene.objects if o.type == "MESH"][0]
scene.frame_set(args.frame)
depsgraph = bpy.context.evaluated_depsgraph_get()
evaluated = water.evaluated_get(depsgraph)
mesh = evaluated.to_mesh()

rows = []
with open(args.csv) as f:
    next(f)
    for line in f:
        col, row, x, y, z = line.strip().split(",")
        rows.append((float(x), float(y), float(z)))
if len(mesh.vertices) != len(rows):
    sys.exit(f"{len(mesh.vertices)} vertices in Blender, {len(rows)} nodes in the CSV")


def close(a, b):
    # f32 printing precision, plus the rounding of Blender's own f32 arithmetic (the
    # glTF importer adds each frame's offset to the rest position; the OBJ's object
    # rotation leaves ~1e-7 in the other axes).
    return abs(a - b) <= 2e-6 * max(1.0, abs(b))


# Every node is compared; a few are printed.
worst = 0.0
bad = []
for i, (x, y, z) in enumerate(rows):
    v = water.matrix_world @ mesh.vertices[i].co
    want = (x, -z, y)
    worst = max(worst, max(abs(v[a] - want[a]) for a in range(3)))
    if not all(close(v[a], want[a]) for a in range(3)):
        bad.append((i, tuple(v), want))
moving = sum(1 for (_, y, _) in rows if abs(y) > 1e-3)
for i in (0, len(rows) // 2, len(rows) - 1):
    print(f"node {i}: blender {tuple(water.matrix_world @ mesh.vertices[i].co)} csv {rows[i]}")
evaluated.to_mesh_clear()
if bad:
    sys.exit(f"{len(bad)} vertices differ at frame {args.frame}, first {bad[:3]}")
if moving == 0:
    sys.exit("the water is flat at this frame: nothing was checked")

if args.floater:
    x, y, z = (float(c) for c in args.floater.split(","))
    body = [o for o in scene.objects if o.name.startswith("floater 0")][0]
    got = body.matrix_world.translation
    if not (close(got[0], x) and close(got[1], -z) and close(got[2], y)):
        sys.exit(f"floater 0 at {tuple(got)}, expected {(x, -z, y)}")
    print(f"floater 0 at {tuple(got)}")
    # Its orientation: the rotation key of this frame as the file holds it, turned from
    # y-up to z-up (M ↦ C M Cᵀ with C: (x, y, z) ↦ (x, −z, y)), against Blender's pose.
    want = rotation_key(args.glb, "floater 0", args.frame)
    c = mathutils.Matrix(((1, 0, 0), (0, 0, -1), (0, 1, 0)))
    w, qx, qy, qz = want[3], want[0], want[1], want[2]
    expected = c @ mathutils.Quaternion((w, qx, qy, qz)).to_matrix() @ c.transposed()
    pose = body.matrix_world.to_3x3()
    off = max(abs(pose[i][j] - expected[i][j]) for i in range(3) for j in range(3))
    if off > 1e-5:
        sys.exit(f"floater 0 turned {pose}, the file says {expected} (key {want})")
    if want == [0.0, 0.0, 0.0, 1.0]:
        sys.exit("floater 0 has not turned at this frame: its rotation was not checked")
    print(f"floater 0 turned as its rotation key {want} says (largest difference {off:g})")

print(f"BAKE OK: {len(rows)} vertices at frame {args.frame} (largest difference {worst:g}), "
      f"{moving} of them off the rest plane")
