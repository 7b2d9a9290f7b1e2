"""Builds Crytek Sponza lit as `bmfr render -s sponza-atrium` lights it, for Cycles, and saves it.

    blender -b --factory-startup --python tools/blender/make_sponza_scene.py -- OUT.blend
            [--gltf PATH] [--frames N] [--size WxH]

The glTF (default ../shared/scenes/sponza/Sponza.gltf) without its roof; a steep sun (0.53
degrees, 30/28/25 W/m^2) along the atrium's long axis from the end the camera looks towards;
a constant sky (radiance 3.0/3.5/4.5) through a portal over the opening; four bounces,
unclamped, no glossy blur. The camera moves as sponza-atrium's does over its 60 frames, of
which frames 1..N are kept (default 24). glTF is y-up and Blender z-up: (x, y, z) -> (x, -z, y).
"""
import argparse
import math
import os
import sys

import bpy
import numpy
from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_GLTF = os.path.join(HERE, "..", "..", "..", "shared", "scenes", "sponza", "Sponza.gltf")
# sponza-atrium's camera (src/render/scene_description.cpp), glTF coordinates, frames 0 and 59.
CAMERA_PATH = (((9.0, 5.5, -2.0), (-10.0, 10.0, 1.5)), ((3.0, 5.5, -2.0), (-16.0, 10.0, 1.0)))
SUN_TOWARDS = (-0.3, 1.0, 0.05)
SUN_IRRADIANCE = (30.0, 28.0, 25.0)
SKY_RADIANCE = (3.0, 3.5, 4.5)
PORTAL = ((-1.45, 22.3, -0.9), 26.2, 6.8)  # centre, x and z extent of the atrium's opening


def blender(p):
    return (p[0], -p[2], p[1])


def linear(obj):
    for fc in obj.animation_data.action.fcurves:
        for k in fc.keyframe_points:
            k.interpolation = "LINEAR"


def animate(obj, a, b, frames):
    """Keys obj at a on frame 1 and where the 60-frame path has it on frame N."""
    t = (frames - 1) / 59.0
    for frame, p in ((1, a), (frames, [x + t * (y - x) for x, y in zip(a, b)])):
        obj.location = blender(p)
        obj.keyframe_insert("location", frame=frame)
    linear(obj)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="make_sponza_scene.py", description=__doc__.split("\n")[0])
    p.add_argument("output", help=".blend file to write")
    p.add_argument("--gltf", default=DEFAULT_GLTF, help="Sponza.gltf (default: ../shared's)")
    p.add_argument("--frames", type=int, default=24, help="frames 1..N, 2 to 60 (default 24)")
    p.add_argument("--size", default="320x180", help="WxH (default 320x180)")
    a = p.parse_args(argv)
    try:
        a.width, a.height = (int(v) for v in a.size.split("x"))
    except ValueError:
        p.error(f"--size {a.size}: expected WxH, as 320x180")
    if a.width < 1 or a.height < 1 or not 2 <= a.frames <= 60:
        p.error("the size must be at least 1x1 and the frames 2 to 60")
    if not os.path.exists(a.gltf):
        print(f"make_sponza_scene.py: {a.gltf} not found (give --gltf PATH)", file=sys.stderr)
        sys.exit(1)
    return a


def main():
    args = parse_args()
    out = os.path.abspath(args.output)
    gltf, frames, width, height = args.gltf, args.frames, args.width, args.height
    bpy.ops.wm.read_factory_settings(use_empty=True)
    # Debian's Blender 3.4 importer uses np.bool, which NumPy 1.24 to 1.26 do not have.
    if "bool" not in numpy.__dict__:
        numpy.bool = numpy.bool_
    bpy.ops.import_scene.gltf(filepath=os.path.abspath(gltf))
    scene = bpy.context.scene
    roof = [o for o in scene.objects if o.name.split(".")[0] == "Roof"]
    for o in roof:
        bpy.data.objects.remove(o, do_unlink=True)

    sun_data = bpy.data.lights.new("sun", "SUN")
    d = blender(SUN_TOWARDS)
    peak = max(SUN_IRRADIANCE)
    sun_data.energy = peak
    sun_data.color = [c / peak for c in SUN_IRRADIANCE]
    sun_data.angle = math.radians(0.53)
    sun = bpy.data.objects.new("sun", sun_data)
    scene.collection.objects.link(sun)
    # A sun light shines along its local -z: turn +z towards the sun.
    sun.rotation_mode = "QUATERNION"
    sun.rotation_quaternion = Vector(d).to_track_quat("Z", "Y")

    portal_data = bpy.data.lights.new("sky portal", "AREA")
    portal_data.shape = "RECTANGLE"
    portal_data.size, portal_data.size_y = PORTAL[1], PORTAL[2]
    portal_data.cycles.is_portal = True
    portal = bpy.data.objects.new("sky portal", portal_data)
    portal.location = blender(PORTAL[0])  # an area light faces its local -z: down
    scene.collection.objects.link(portal)

    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (*SKY_RADIANCE, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world

    target = bpy.data.objects.new("camera target", None)
    scene.collection.objects.link(target)
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(cam)
    cam.data.sensor_fit = "VERTICAL"
    cam.data.angle_y = math.radians(60.0)
    cam.data.clip_start = 0.05
    track = cam.constraints.new("TRACK_TO")
    track.target = target
    track.track_axis, track.up_axis = "TRACK_NEGATIVE_Z", "UP_Y"
    animate(cam, CAMERA_PATH[0][0], CAMERA_PATH[1][0], frames)
    animate(target, CAMERA_PATH[0][1], CAMERA_PATH[1][1], frames)
    scene.camera = cam

    scene.frame_start, scene.frame_end = 1, frames
    scene.render.engine = "CYCLES"
    scene.render.resolution_x, scene.render.resolution_y = width, height
    c = scene.cycles
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = 4
    c.transparent_max_bounces = 16
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.use_denoising = False  # Debian's Blender has no OpenImageDenoise
    scene.view_settings.view_transform = "Standard"
    bpy.ops.wm.save_as_mainfile(filepath=out)
    print(f"make_sponza_scene.py: wrote {out} ({width}x{height}, frames 1-{frames})")


main()
