"""Blender round trip: build a tiny room in Blender, render it with Cycles through
tools/blender/render_sequence.py, denoise the folder with `bmfr denoise`, and score it.

Checks: the multilayer EXRs are read through the default pass mapping; every frame's
view-projection maps each pixel's world position to its pixel centre plus the recorded jitter;
the moving sphere's motion vectors and previous positions are those of its known path
(motion_check.py); BMFR and SVGF both beat the noisy input against the Cycles reference. Exit 77
(skipped) when Blender is not installed (blender_run.py: Debian's blender, or PyPI's bpy)."""
import json
import os
import shutil
import sys
import tempfile

import numpy as np

import bmfr
import motion_check

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../tools/blender"))
import blender_run  # noqa: E402

CLI = os.environ["BMFR_CLI"]


def projection_error(frame):
    """Largest distance, pixels, between where position projects and the pixel's own sample
    position (its centre plus the jitter)."""
    h, w, _ = frame["position"].shape
    u, v = motion_check.project(frame["view_projection"], frame["position"].astype(np.float64),
                                w, h, frame["jitter"])
    ys, xs = np.mgrid[0:h, 0:w]
    return float(max(np.abs(u - xs).max(), np.abs(v - ys).max()))


def main():
    blender_run.require_blender()
    work = tempfile.mkdtemp(prefix="bmfr_blender_")
    blend, seq = os.path.join(work, "room.blend"), os.path.join(work, "seq")
    print(f"Blender {blender_run.info()[0]}")
    blender_run.make_scene(blend, 4, "32x18")
    blender_run.render(blend, seq, "--reference-spp", 64)
    # The sphere moves: Cycles' vectors and the previous positions against its known path.
    motion_check.check(seq, blend + ".json")

    frames = list(bmfr.read_sequence(seq))
    assert len(frames) == 4, len(frames)
    for f in frames:
        assert f["color"].shape == (18, 32, 3)
        err = projection_error(f)
        assert err < 1e-3, f"frame {f['index']}: positions project {err} px off"
        n = np.linalg.norm(f["normal"], axis=-1)
        assert abs(n.mean() - 1) < 1e-3, "the Normal pass is not unit length"
        assert 0 < f["albedo"].mean() < 1 and f["reference"].mean() > 0
    jitters = {tuple(f["jitter"]) for f in frames}
    assert len(jitters) == 4, "the jitter does not change per frame"

    scores = {}
    for name in ("bmfr", "svgf"):
        out = os.path.join(work, name)
        blender_run.run(CLI, "denoise", seq, "-o", out, "--filter", name, "--no-png", "-q")
        report = json.load(open(os.path.join(out, "report.json")))
        scores[name] = report["scores"]
    table = json.loads(blender_run.run(CLI, "eval", "-r", seq, "-m", "noisy", "-m",
                           f"bmfr={os.path.join(work, 'bmfr')}", "-m",
                           f"svgf={os.path.join(work, 'svgf')}", "-o", os.path.join(work, "eval"),
                           "--json", "-q"))
    print("Blender round trip, 32x18, 4 frames, reference 64 spp (tone-mapped RMSE, SSIM, FLIP):")
    for name, m in table["methods"].items():
        mean = m["mean"]
        print(f"  {name:<6} rmse {mean['rmse']:.4f}  ssim {mean['ssim']:.4f}  "
              f"flip {mean['flip']:.4f}  temporal {mean['temporal_error'] or 0:.4f}")
    noisy = scores["bmfr"]["noisy_rmse"]
    for name, s in scores.items():
        assert s["rmse"] < 0.7 * noisy, f"{name} rmse {s['rmse']} vs noisy {noisy}"
    shutil.rmtree(work)
    print("blender round trip passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
