"""bmfr against Blender's own per-frame denoiser on an animated Cycles scene.

    PYTHONPATH=build/python python3 tools/blender/compare.py OUT [--size 320x180] [--frames 24]
            [--reference-spp 1024] [--bmfr build/bmfr] [--video] [--no-jitter]

Builds the scene of make_test_scene.py (a checkered sphere crossing a room, a panning camera, a
lamp in view), renders it at 1 spp with Cycles through render_sequence.py (with Cycles' own
OIDN denoiser on where this Blender has it: PyPI's bpy, through $BLENDER_PYTHON; Debian's 3.4
has none, and then --oidn-peer scores OIDN as `bmfr eval --oidn` runs it), denoises it with
each filter with Cycles' vectors and by the camera path alone (--no-motion), and scores every
method against the reference with `bmfr eval` (tone-mapped RMSE, FLIP, temporal error and change
error) and in the sphere's trail: the pixels the sphere covers in this frame or the last. Prints
one markdown table and writes OUT/comparison.json; --video adds eval's side-by-side video.
"""
import argparse
import json
import os
import shutil
import sys
import warnings

import numpy as np

import bmfr
import blender_run
import sphere_path

FILTERS = [("bmfr", "quality"), ("bmfr", "faithful"), ("svgf", "quality"), ("walr", "quality")]
FIRST_SCORED = 4  # the trail is scored from here: the first frames have no history to ghost


def read_passes(seq, path):
    """The noisy frames, the references and, per frame, the pixels on the sphere: one read."""
    entries = json.load(open(os.path.join(seq, "sequence.json")))["frames"]
    noisy, refs, masks = [], [], []
    for e, f in zip(entries, bmfr.read_sequence(seq)):
        noisy.append(f["color"])
        refs.append(f["reference"])
        masks.append(sphere_path.on_sphere(f["position"], path, sphere_path.blender_frame(e)))
    return noisy, refs, masks


def tonemap(x):
    return np.clip(np.maximum(x, 0) ** (1 / 2.2), 0, 1)


def trail_rmse(frames, references, masks):
    """Tone-mapped RMSE over the trail (the sphere now or in the previous frame), frames
    FIRST_SCORED on."""
    sq, n = 0.0, 0
    for k in range(FIRST_SCORED, len(frames)):
        band = masks[k] | masks[k - 1]
        e = tonemap(frames[k]) - tonemap(references[k])
        sq += float((e[band] ** 2).sum())
        n += int(band.sum()) * 3
    return (sq / n) ** 0.5


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("output")
    p.add_argument("--size", default="320x180")
    p.add_argument("--frames", type=int, default=24)
    p.add_argument("--reference-spp", type=int, default=1024)
    p.add_argument("--bmfr", default=os.environ.get("BMFR_CLI", "bmfr"))
    p.add_argument("--video", action="store_true")
    p.add_argument("--no-jitter", action="store_true")
    p.add_argument("--no-flip", action="store_true", help="skip FLIP (the slowest metric)")
    p.add_argument("--reuse", action="store_true",
                   help="score an earlier run's render in OUTPUT again (new filters, settings)")
    p.add_argument("--oidn-peer", action="store_true",
                   help="where Blender has no OIDN: score OIDN as `bmfr eval --oidn` runs it "
                        "(scripts/install-oidn.sh installs it)")
    p.add_argument("--filters", default=",".join(f"{f}:{s}" for f, s in FILTERS),
                   help="FILTER:PRESET,... (default: %(default)s)")
    a = p.parse_args(argv)
    # The render has Cycles' denoiser on by design: the reader's note about it is expected.
    warnings.filterwarnings("ignore", message="Cycles' own denoiser was on")
    if not blender_run.blender_command():
        sys.exit("compare.py: no Blender (install Debian's blender, or set BLENDER_PYTHON)")
    out = os.path.abspath(a.output)
    os.makedirs(out, exist_ok=True)
    blend, seq = os.path.join(out, "scene.blend"), os.path.join(out, "passes")
    version, oidn = blender_run.info()
    print(f"compare: Blender {version} (Cycles' own OIDN: {'yes' if oidn else 'no'})", flush=True)
    if a.reuse and os.path.exists(os.path.join(seq, "sequence.json")):
        print(f"compare: reusing the render in {seq}", flush=True)
    else:
        blender_run.make_scene(blend, a.frames, a.size)
        print(f"compare: rendering {a.frames} frames at {a.size}, reference {a.reference_spp} "
              "spp", flush=True)
        options = ["--reference-spp", a.reference_spp] + (["--denoiser"] if oidn else [])
        blender_run.render(blend, seq, *(options + (["--no-jitter"] if a.no_jitter else [])))
    path = json.load(open(blend + ".json"))["sphere"]

    methods = {}  # name -> denoise output folder (or sequence whose colour is the method)
    for spec in a.filters.split(","):
        f, preset = spec.split(":")
        for vectors in (True, False):
            name = f"{f}{'-faithful' if preset == 'faithful' else ''}{'' if vectors else '-camera'}"
            dest = os.path.join(out, name)
            print(f"compare: denoising {name}", flush=True)
            blender_run.run(a.bmfr, "denoise", seq, "-o", dest, "--filter", f, "--preset",
                            preset, "--no-png", "--overwrite", "-q",
                            *([] if vectors else ["--no-motion"]))
            methods[name] = dest
    eval_args = []
    if oidn:
        # Cycles' denoised Combined, as a sequence whose colour it is.
        cyc = os.path.join(out, "cycles-oidn")
        os.makedirs(cyc, exist_ok=True)
        doc = json.load(open(os.path.join(seq, "sequence.json")))
        for fr in doc["frames"]:
            for key, v in list(fr.items()):
                if isinstance(v, str) and v.endswith(".exr"):
                    fr[key] = "../passes/" + v
                elif isinstance(v, dict):
                    v["file"] = "../passes/" + v["file"]
        doc["layers"] = {"color": "ViewLayer.Combined"}
        json.dump(doc, open(os.path.join(cyc, "sequence.json"), "w"), indent=1)
        methods["cycles-oidn"] = cyc
    elif a.oidn_peer:
        eval_args.append("--oidn")
    report = os.path.join(out, "eval")
    if os.path.isdir(report):
        shutil.rmtree(report)
    print("compare: scoring", flush=True)
    table = json.loads(blender_run.run(
        a.bmfr, "eval", "-r", seq, "-m", "noisy", *sum((["-m", f"{n}={d}"] for n, d in
                                                        methods.items()), []),
        "-o", report, "--json", "-q", *eval_args, *(["--video"] if a.video else []),
        *(["--no-flip"] if a.no_flip else [])))

    noisy, refs, masks = read_passes(seq, path)
    trail = {"noisy": trail_rmse(noisy, refs, masks)}
    for name, dest in methods.items():
        if name == "cycles-oidn":  # a sequence whose colour is Cycles' result
            frames = [f["color"] for f in bmfr.read_sequence(dest)]
        else:
            frames = [bmfr.read_exr(os.path.join(dest, f"denoised_{k:04d}.exr"))
                      for k in range(len(refs))]
        trail[name] = trail_rmse(frames, refs, masks)

    rows = []
    noisy_rmse = table["methods"]["noisy"]["mean"]["rmse"]
    print(f"\nBlender {version} Cycles, {a.size}, {a.frames} frames, 1 spp, "
          f"{'unjittered' if a.no_jitter else 'jittered'}, reference {a.reference_spp} spp; "
          f"reference's own temporal error {table['reference_temporal_error']:.4f}\n")
    print("| method | RMSE | RMSE / noisy | FLIP | temporal error | change error | trail RMSE |")
    print("|---|---|---|---|---|---|---|")
    for name, m in table["methods"].items():
        mean = m["mean"]
        t = trail.get(name)
        rows.append({"method": name, **mean, "trail_rmse": t})
        flip = f"{mean['flip']:.4f}" if mean.get("flip") is not None else "-"
        print(f"| {name} | {mean['rmse']:.4f} | {mean['rmse'] / noisy_rmse:.3f} | {flip} | "
              f"{mean['temporal_error'] or 0:.4f} | {mean['temporal_change_error'] or 0:.4f} | "
              f"{'-' if t is None else f'{t:.4f}'} |")
    ratios = {}
    for name in methods:
        if name.endswith("-camera"):
            base = name[:-len("-camera")]
            ratios[base] = trail[name] / trail[base]
    print("\ntrail RMSE, camera path over Cycles' vectors: "
          + ", ".join(f"{n} {r:.2f}x" for n, r in ratios.items()))
    json.dump({"blender": version, "size": a.size, "frames": a.frames,
               "reference_spp": a.reference_spp, "jitter": not a.no_jitter, "rows": rows,
               "trail_ratio": ratios}, open(os.path.join(out, "comparison.json"), "w"), indent=1)
    return ratios


if __name__ == "__main__":
    main()
