"""Renders a Blender scene's animation with Cycles into a bmfr sequence folder.

    blender -b scene.blend --python tools/blender/render_sequence.py -- OUT
    python3 tools/blender/render_sequence.py -- OUT --blend scene.blend     (PyPI's bpy)
            [--frames A:B] [--spp N] [--reference-spp N] [--device CPU|GPU]
            [--width W --height H] [--no-jitter] [--motion auto|on|off] [--denoiser] [--seed S]
            [--visibility auto|off]

Frames A..B-1 are Blender frame numbers (default: the scene's range) and name the files
(frame_0001.exr ...). `bmfr denoise OUT -o RESULT` then reads the folder directly. What it
writes and the conventions: bmfr_addon/sequence.py and docs/blender.md. Exits 1 with the
reasons when the scene cannot be rendered faithfully (motion blur, depth of field, a
transparent film, no camera).
"""
import argparse
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bmfr_addon import sequence  # noqa: E402


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="render_sequence.py", description=__doc__.split("\n")[0])
    p.add_argument("output", help="sequence folder to write")
    p.add_argument("--frames", help="A:B, Blender frames A..B-1 (default: the scene's)")
    p.add_argument("--spp", type=int, default=1, help="samples per pixel (default 1)")
    p.add_argument("--reference-spp", type=int, default=0, help="0 = no reference")
    p.add_argument("--device", default="CPU", choices=["CPU", "GPU"],
                   help="CPU, or GPU: the first GPU Cycles finds (OptiX, CUDA, HIP, ...)")
    p.add_argument("--width", type=int)
    p.add_argument("--height", type=int)
    p.add_argument("--no-jitter", action="store_true")
    p.add_argument("--motion", default="auto", choices=["auto", "on", "off"],
                   help="Cycles' Vector pass and previous positions: auto = when anything moves")
    p.add_argument("--denoiser", action="store_true",
                   help="also Cycles' own denoiser (OIDN) per frame: Combined is then its result "
                        "and bmfr reads the Noisy Image pass")
    p.add_argument("--visibility", default="auto", choices=["auto", "off"],
                   help="auto: also the brightest sun's visibility pass, when there is a sun")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--blend", help="open this .blend first (for the bpy module from PyPI, which "
                                   "has no command line to name it on)")
    p.add_argument("-q", "--quiet", action="store_true")
    return p.parse_args(argv)


def main():
    args = parse_args()
    if args.blend:
        bpy.ops.wm.open_mainfile(filepath=args.blend)
    frames = None
    if args.frames:
        a, sep, b = args.frames.partition(":")
        if not sep:
            sys.exit(f"render_sequence.py: --frames {args.frames}: expected A:B (A: or :B)")
        try:
            frames = (int(a) if a else None, int(b) if b else None)
        except ValueError:
            sys.exit(f"render_sequence.py: --frames {args.frames}: expected A:B")
    scene = bpy.context.scene
    if frames:
        frames = (frames[0] if frames[0] is not None else scene.frame_start,
                  frames[1] if frames[1] is not None else scene.frame_end + 1)
    opts = sequence.Options(spp=args.spp, reference_spp=args.reference_spp, frames=frames,
                            width=args.width, height=args.height, jitter=not args.no_jitter,
                            seed=args.seed, device=args.device, motion=args.motion,
                            denoiser=args.denoiser, visibility=args.visibility)

    def progress(done, total, text):
        if not args.quiet:
            print(f"render_sequence: {text}", flush=True)

    try:
        s = sequence.render_sequence(scene, args.output, opts, progress)
    except sequence.SequenceError as e:
        print(f"render_sequence.py: {e}", file=sys.stderr, flush=True)
        sys.exit(1)
    if s["without_previous_position"]:
        print("render_sequence.py: warning: no previous position for "
              + ", ".join(s["without_previous_position"])
              + " (no node material): their pixels read as static",
              file=sys.stderr)
    if not args.quiet:
        moving = ", ".join(s["moving"]) or "nothing"
        print(f"render_sequence: wrote {s['frames']} frames of {s['width']}x{s['height']} "
              f"(Blender frames {s['first']}-{s['first'] + s['frames'] - 1}, {s['device']}) to "
              f"{s['output']}; moving: {moving}; motion vectors "
              f"{'written' if s['motion'] else 'not written'}; visibility "
              f"{'of ' + repr(s['visibility']) if s['visibility'] else 'not written'}")


main()
