"""Builds a tiny closed room for the round-trip test and saves it as a .blend file.

    blender -b --factory-startup --python tools/blender/make_test_scene.py -- OUT.blend

A box of five coloured walls and a ceiling, an emissive panel below the ceiling, a cube and a
sphere, and a camera that moves over frames 1 to 4. No world light reaches inside.
"""
import math
import sys

import bpy


def material(name, color, emission=None):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1)
    bsdf.inputs["Roughness"].default_value = 0.8
    if emission:
        bsdf.inputs["Emission"].default_value = (*emission, 1)
        bsdf.inputs["Emission Strength"].default_value = 12.0
    return m


def plane(name, location, rotation, size, mat):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(mat)
    return obj


def main():
    out = sys.argv[sys.argv.index("--") + 1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    white = material("white", (0.75, 0.75, 0.72))
    red = material("red", (0.7, 0.1, 0.08))
    green = material("green", (0.1, 0.6, 0.12))
    lamp = material("lamp", (0.0, 0.0, 0.0), emission=(1.0, 0.9, 0.75))
    half = 1.0
    plane("floor", (0, 0, 0), (0, 0, 0), 2 * half, white)
    plane("ceiling", (0, 0, 2 * half), (math.pi, 0, 0), 2 * half, white)
    plane("back", (0, half, half), (math.pi / 2, 0, 0), 2 * half, white)
    plane("front", (0, -half, half), (-math.pi / 2, 0, 0), 2 * half, white)
    plane("left", (-half, 0, half), (0, math.pi / 2, 0), 2 * half, red)
    plane("right", (half, 0, half), (0, -math.pi / 2, 0), 2 * half, green)
    plane("panel", (0, 0, 2 * half - 0.02), (math.pi, 0, 0), 0.6, lamp)
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(-0.35, 0.2, 0.25),
                                    rotation=(0, 0, 0.4))
    bpy.context.active_object.data.materials.append(white)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.28, location=(0.4, -0.1, 0.28))
    bpy.context.active_object.data.materials.append(white)

    bpy.ops.object.camera_add(location=(0, -0.95, 1.0), rotation=(math.radians(88), 0, 0))
    cam = bpy.context.active_object
    cam.data.lens = 16
    scene.camera = cam
    for frame, x in ((1, -0.12), (4, 0.12)):
        cam.location.x = x
        cam.keyframe_insert("location", frame=frame)
    scene.frame_start, scene.frame_end = 1, 4
    scene.render.resolution_x, scene.render.resolution_y = 32, 18
    world = bpy.data.worlds.new("black")
    world.color = (0, 0, 0)
    scene.world = world
    scene.cycles.max_bounces = 4
    bpy.ops.wm.save_as_mainfile(filepath=out)


main()
