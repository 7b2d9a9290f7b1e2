"""Renders a Blender scene's animation with Cycles into a bmfr sequence folder.

    blender -b scene.blend --python tools/blender/render_sequence.py -- OUT
            [--frames A:B] [--width W --height H] [--reference-spp N] [--no-jitter] [--seed S]

Per frame it writes one multilayer EXR at 1 sample per pixel with the passes BMFR needs
(Combined, Denoising Albedo, Normal, Position, Emit; Cycles names them so), optionally a
reference of N samples per pixel, and records in OUT/sequence.json the camera's
view-projection matrix in the library's convention and the frame's sub-pixel jitter.
`bmfr denoise OUT -o RESULT` then reads the folder directly.

Conventions (those of bmfr's FrameInput):
- view_projection is row-major and acts on column vectors; NDC x grows to the right and NDC y
  grows downwards, so Blender's OpenGL projection gets its second row negated.
- The primary ray of pixel (x, y) goes through the screen point (x + 0.5 + jx, y + 0.5 + jy),
  pixels, y down. Cycles' pixel filter is shrunk to 0.01 px so that every ray of a frame goes
  through that one point, and the jitter (Halton 2, 3, as bmfr render) is made with the camera's
  lens shift. The jitter written is the one realised, read back from the two projections.
- The reference is rendered at the pixel centres (no shift), as bmfr render's references are.
"""
import argparse
import json
import os
import sys

import bpy

PASS_NOTE = "Combined, Denoising Albedo, Normal, Position, Emit (Cycles pass names)"


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="render_sequence.py", description=__doc__.split("\n")[0])
    p.add_argument("output", help="sequence folder to write")
    p.add_argument("--frames", help="A:B, Blender frame numbers A..B-1 (default: the scene's)")
    p.add_argument("--width", type=int)
    p.add_argument("--height", type=int)
    p.add_argument("--reference-spp", type=int, default=0, help="0 = no reference")
    p.add_argument("--no-jitter", action="store_true")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("-q", "--quiet", action="store_true")
    return p.parse_args(argv)


def halton(index, base):
    f, r = 1.0, 0.0
    while index > 0:
        f /= base
        r += f * (index % base)
        index //= base
    return r


def projection(camera, depsgraph, render):
    return camera.calc_matrix_camera(depsgraph, x=render.resolution_x, y=render.resolution_y,
                                     scale_x=render.pixel_aspect_x, scale_y=render.pixel_aspect_y)


def view_projection(camera, depsgraph, render):
    """World to clip in bmfr's convention (NDC y down)."""
    m = projection(camera, depsgraph, render) @ camera.matrix_world.inverted()
    rows = [list(m[r]) for r in range(4)]
    rows[1] = [-v for v in rows[1]]
    return rows


def write_json_atomically(path, doc):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)


def render_to(scene, path):
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    if not os.path.exists(path):
        sys.exit(f"render_sequence.py: Cycles did not write {path}")


def main():
    args = parse_args()
    scene = bpy.context.scene
    render = scene.render
    if scene.camera is None:
        sys.exit("render_sequence.py: the scene has no active camera")
    if args.width:
        render.resolution_x = args.width
    if args.height:
        render.resolution_y = args.height
    render.resolution_percentage = 100
    if render.resolution_x <= 0 or render.resolution_y <= 0:
        sys.exit("render_sequence.py: zero image size")
    first, last = scene.frame_start, scene.frame_end + 1
    if args.frames:
        a, _, b = args.frames.partition(":")
        first, last = int(a or first), int(b or last)
    if last <= first:
        sys.exit(f"render_sequence.py: empty frame range {first}:{last}")

    render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.filter_width = 0.01
    render.use_persistent_data = True
    render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    render.image_settings.color_depth = "32"
    render.image_settings.exr_codec = "ZIP"
    render.use_file_extension = False
    layer = bpy.context.view_layer
    layer.use_pass_combined = True
    layer.use_pass_normal = True
    layer.use_pass_position = True
    layer.use_pass_emit = True
    layer.cycles.denoising_store_passes = True

    out = os.path.abspath(args.output)
    os.makedirs(out, exist_ok=True)
    cam = scene.camera
    w, h = render.resolution_x, render.resolution_y
    frames = []
    doc = {"format": "bmfr-sequence", "version": 1, "width": w, "height": h,
           "color_is_demodulated": False,
           "generator": f"Blender {bpy.app.version_string} Cycles via "
                        f"tools/blender/render_sequence.py; passes {PASS_NOTE}",
           "frames": frames}
    for n, frame in enumerate(range(first, last)):
        scene.frame_set(frame)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        shift = (cam.data.shift_x, cam.data.shift_y)
        vp = view_projection(cam, depsgraph, render)
        p0 = projection(cam, depsgraph, render)
        jitter = (0.0, 0.0) if args.no_jitter else (halton(n + 1, 2) - 0.5, halton(n + 1, 3) - 0.5)
        # Lens shift is in units of the larger image side; +x moves the view right and +y up.
        side = max(w, h)
        cam.data.shift_x = shift[0] + jitter[0] / side
        cam.data.shift_y = shift[1] - jitter[1] / side
        depsgraph = bpy.context.evaluated_depsgraph_get()
        p1 = projection(cam, depsgraph, render)
        realised = ((p1[0][2] - p0[0][2]) * w / 2, -(p1[1][2] - p0[1][2]) * h / 2)
        cycles.samples = 1
        cycles.seed = args.seed * 7919 + n
        name = f"frame_{n:04d}.exr"
        render_to(scene, os.path.join(out, name))
        cam.data.shift_x, cam.data.shift_y = shift
        entry = {"color": name, "albedo": name, "normal": name, "position": name,
                 "emission": name, "view_projection": vp, "jitter": list(realised)}
        if args.reference_spp > 0:
            cycles.samples = args.reference_spp
            cycles.seed = args.seed * 7919 + n + 1000003
            ref = f"reference_{n:04d}.exr"
            render_to(scene, os.path.join(out, ref))
            entry["reference"] = ref
        frames.append(entry)
        write_json_atomically(os.path.join(out, "sequence.json"), doc)
        if not args.quiet:
            print(f"render_sequence: frame {n + 1}/{last - first} (Blender frame {frame})",
                  flush=True)
    if not args.quiet:
        print(f"render_sequence: wrote {len(frames)} frames of {w}x{h} to {out}")


main()
