"""Builds a small closed room for the Blender tests and the demo, and saves it as a .blend file.

    blender -b --factory-startup --python tools/blender/make_test_scene.py -- OUT.blend
            [--frames N] [--size WxH]

A box of five coloured walls and a ceiling, an emissive panel below the ceiling and a
small one on the back wall (in view), a
cube, and a sphere that moves along a straight line at a constant velocity while the camera
pans, over frames 1 to N (default 4). OUT.blend.json records the sphere's path, which the tests
check motion vectors and previous positions against. No world light reaches inside.
"""
import json
import math
import sys

import bpy

SPHERE_START = (0.45, -0.42, 0.28)  # passes in front of the cube, never through it
SPHERE_RADIUS = 0.26


def material(name, color, emission=None, checker=False):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1)
    bsdf.inputs["Roughness"].default_value = 0.8
    if emission:
        name = "Emission Color" if "Emission Color" in bsdf.inputs else "Emission"
        bsdf.inputs[name].default_value = (*emission, 1)
        bsdf.inputs["Emission Strength"].default_value = 12.0
    if checker:  # texture detail that history from the wrong place shows
        tex = m.node_tree.nodes.new("ShaderNodeTexChecker")
        tex.inputs["Scale"].default_value = 6.0
        tex.inputs["Color1"].default_value = (*color, 1)
        tex.inputs["Color2"].default_value = (0.08, 0.08, 0.3, 1)
        m.node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    return m


def plane(name, location, rotation, size, mat):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(mat)
    return obj


def linear(obj):
    for fc in obj.animation_data.action.fcurves:
        for k in fc.keyframe_points:
            k.interpolation = "LINEAR"


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    out = argv[0]
    frames = int(argv[argv.index("--frames") + 1]) if "--frames" in argv else 4
    size = argv[argv.index("--size") + 1] if "--size" in argv else "32x18"
    width, height = (int(v) for v in size.split("x"))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    white = material("white", (0.75, 0.75, 0.72))
    red = material("red", (0.7, 0.1, 0.08))
    green = material("green", (0.1, 0.6, 0.12))
    orange = material("orange", (0.8, 0.45, 0.1), checker=True)
    lamp = material("lamp", (0.0, 0.0, 0.0), emission=(1.0, 0.9, 0.75))
    half = 1.0
    plane("floor", (0, 0, 0), (0, 0, 0), 2 * half, white)
    plane("ceiling", (0, 0, 2 * half), (math.pi, 0, 0), 2 * half, white)
    plane("back", (0, half, half), (math.pi / 2, 0, 0), 2 * half, white)
    plane("front", (0, -half, half), (-math.pi / 2, 0, 0), 2 * half, white)
    plane("left", (-half, 0, half), (0, math.pi / 2, 0), 2 * half, red)
    plane("right", (half, 0, half), (0, -math.pi / 2, 0), 2 * half, green)
    plane("panel", (0, 0, 2 * half - 0.02), (math.pi, 0, 0), 0.6, lamp)
    plane("lamp", (0.3, half - 0.02, 1.45), (math.pi / 2, 0, 0), 0.3, lamp)  # in view
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(-0.35, 0.2, 0.25),
                                    rotation=(0, 0, 0.4))
    bpy.context.active_object.data.materials.append(white)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=SPHERE_RADIUS, location=SPHERE_START)
    sphere = bpy.context.active_object
    sphere.name = "sphere"
    sphere.data.materials.append(orange)
    bpy.ops.object.shade_smooth()
    # The sphere crosses the room at a constant velocity: 0.7 scene units over the frames.
    velocity = (-0.7 / max(frames - 1, 1), 0.0, 0.0)
    for frame in (1, frames):
        sphere.location = [s + v * (frame - 1) for s, v in zip(SPHERE_START, velocity)]
        sphere.keyframe_insert("location", frame=frame)
    linear(sphere)

    bpy.ops.object.camera_add(location=(0, -0.95, 0.85), rotation=(math.radians(78), 0, 0))
    cam = bpy.context.active_object
    cam.data.lens = 14
    scene.camera = cam
    for frame, x in ((1, -0.12), (frames, 0.12)):
        cam.location.x = x
        cam.keyframe_insert("location", frame=frame)
    linear(cam)
    scene.frame_start, scene.frame_end = 1, frames
    scene.render.resolution_x, scene.render.resolution_y = width, height
    world = bpy.data.worlds.new("black")
    world.color = (0, 0, 0)
    scene.world = world
    scene.cycles.max_bounces = 4
    bpy.ops.wm.save_as_mainfile(filepath=out)
    with open(out + ".json", "w") as f:
        json.dump({"sphere": {"start": SPHERE_START, "velocity_per_frame": velocity,
                              "radius": SPHERE_RADIUS, "first_frame": 1}}, f, indent=1)


main()
