"""Renders one frame of a `springwater bake` glTF in Blender with Cycles on the CPU: the
picture docs/bake-blender.png. Made with:

    springwater bake --size 129x129 --frames 48 --fps 24 --rain 1 --wake \
        --drop 40,70,3,4 --drop 90,40,3,4 --drop 70,90,2,3 --out water.glb
    blender -b --python docs/bake_render.py -- water.glb 24 docs/bake-blender.png
"""
import math
import sys

import numpy

numpy.bool = bool  # Blender 3.4's glTF importer with numpy 1.24

import bpy  # noqa: E402

glb, frame, out = sys.argv[sys.argv.index("--") + 1:][:3]
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.fps = 24
bpy.ops.import_scene.gltf(filepath=glb, import_shading="SMOOTH")
water = [o for o in scene.objects if o.type == "MESH"][0]
# The pool spans x 0..128 and (Blender's y, glTF's -z) 0..-128.
size = max(water.dimensions.x, water.dimensions.y)
centre = (size / 2, -size / 2, 0)

# Water: clear glass-like with a blue-green tint.
mat = bpy.data.materials.new("water")
mat.use_nodes = True
bsdf = mat.node_tree.nodes["Principled BSDF"]
bsdf.inputs["Base Color"].default_value = (0.6, 0.85, 0.9, 1)
bsdf.inputs["Roughness"].default_value = 0.02
bsdf.inputs["IOR"].default_value = 1.333
bsdf.inputs["Transmission"].default_value = 1.0
water.data.materials.clear()
water.data.materials.append(mat)

# A tiled pool bottom 8 units down.
bpy.ops.mesh.primitive_plane_add(size=size, location=(centre[0], centre[1], -8))
bottom = bpy.context.active_object
tiles = bpy.data.materials.new("tiles")
tiles.use_nodes = True
nodes = tiles.node_tree.nodes
checker = nodes.new("ShaderNodeTexChecker")
checker.inputs["Scale"].default_value = 16
checker.inputs["Color1"].default_value = (0.85, 0.9, 0.95, 1)
checker.inputs["Color2"].default_value = (0.1, 0.35, 0.6, 1)
tiles.node_tree.links.new(checker.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
bottom.data.materials.append(tiles)

bpy.ops.object.light_add(type="SUN", rotation=(math.radians(35), 0, math.radians(30)))
bpy.context.active_object.data.energy = 4
world = bpy.data.worlds.new("sky")
world.use_nodes = True
sky = world.node_tree.nodes.new("ShaderNodeTexSky")
sky.sun_elevation = math.radians(35)
world.node_tree.links.new(sky.outputs["Color"], world.node_tree.nodes["Background"].inputs["Color"])
scene.world = world

bpy.ops.object.camera_add(location=(centre[0] + 0.1 * size, centre[1] - 0.75 * size, 0.22 * size))
cam = bpy.context.active_object
direction = cam.location.copy()
direction.x -= centre[0]
direction.y -= centre[1]
direction.z -= -6
cam.rotation_euler = direction.to_track_quat("Z", "Y").to_euler()
cam.data.lens = 30
scene.camera = cam

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 48
scene.cycles.use_denoising = False
scene.render.resolution_x = 640
scene.render.resolution_y = 360
scene.render.filepath = out
scene.frame_set(int(frame))
bpy.ops.render.render(write_still=True)
