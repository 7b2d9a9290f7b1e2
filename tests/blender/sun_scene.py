"""Builds the visibility test's scene: a floor, a cube floating above it, a leaf-like plane
whose alpha is a checker (half of it lets the sun through), and a sun from a known direction;
the camera looks down at the shadows. OUT.blend.json holds the geometry the test casts
shadow rays against.

    blender -b --factory-startup --python tests/blender/sun_scene.py -- OUT.blend
"""
import json
import math
import sys

import bpy
from mathutils import Vector

SUN_TOWARDS = (1.0, -0.7, 0.55)
CUBE = ((-0.6, 0.3, 0.9), 0.5)   # centre, half side
LEAF = ((0.9, -0.5, 0.5), 0.6)  # centre, half side; horizontal; alpha a 4x4 checker


def main():
    out = sys.argv[sys.argv.index("--") + 1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    white = bpy.data.materials.new("white")
    white.use_nodes = True
    bpy.ops.mesh.primitive_plane_add(size=6, location=(0, 0, 0))
    bpy.context.active_object.data.materials.append(white)
    bpy.ops.mesh.primitive_cube_add(size=2 * CUBE[1], location=CUBE[0])
    bpy.context.active_object.data.materials.append(white)
    leaf = bpy.data.materials.new("leaf")
    leaf.use_nodes = True
    checker = leaf.node_tree.nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = 4.0
    checker.inputs["Color1"].default_value = (1, 1, 1, 1)
    checker.inputs["Color2"].default_value = (0, 0, 0, 1)
    bsdf = leaf.node_tree.nodes["Principled BSDF"]
    leaf.node_tree.links.new(checker.outputs["Fac"], bsdf.inputs["Alpha"])
    bpy.ops.mesh.primitive_plane_add(size=2 * LEAF[1], location=LEAF[0])
    bpy.context.active_object.data.materials.append(leaf)
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.color = (1.0, 0.8, 0.6)  # the pass is white, and the colour is put back
    for frame, energy in ((1, 3.0), (2, 5.0)):  # animated: the pass must not follow it
        sun.data.energy = energy
        sun.data.keyframe_insert("energy", frame=frame)
    sun.data.angle = math.radians(2.0)  # the pass must not depend on it
    sun.rotation_mode = "QUATERNION"
    sun.rotation_quaternion = Vector(SUN_TOWARDS).to_track_quat("Z", "Y")
    scene.collection.objects.link(sun)
    lamp = bpy.data.objects.new("lamp", bpy.data.lights.new("lamp", "POINT"))
    lamp.location = (1.5, 1.5, 2.0)  # another light, which the pass leaves out
    lamp.data.energy = 200.0
    scene.collection.objects.link(lamp)
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    cam.location = (0.0, -2.6, 4.2)
    cam.rotation_euler = (math.radians(32), 0, 0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    world = bpy.data.worlds.new("sky")
    world.color = (0.3, 0.3, 0.35)
    scene.world = world
    scene.frame_start, scene.frame_end = 1, 2
    scene.render.resolution_x, scene.render.resolution_y = 64, 48
    scene.cycles.use_denoising = False
    bpy.ops.wm.save_as_mainfile(filepath=out)
    with open(out + ".json", "w") as f:
        json.dump({"sun_towards": SUN_TOWARDS, "cube": CUBE, "leaf": LEAF}, f)


main()
