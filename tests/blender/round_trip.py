"""Blender round trip: build a tiny room in Blender, render it with Cycles through
tools/blender/render_sequence.py, denoise the folder with `bmfr denoise`, and score it.

Checks: the multilayer EXRs are read through the default pass mapping; every frame's
view-projection maps each pixel's world position to its pixel centre plus the recorded jitter;
BMFR and SVGF both beat the noisy input against the Cycles reference. Exit 77 (skipped) when
Blender is not installed."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

import bmfr

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CLI = os.environ["BMFR_CLI"]
BLENDER = os.environ.get("BLENDER") or shutil.which("blender")


def run(*cmd):
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"failed ({r.returncode}): {' '.join(map(str, cmd))}\n{r.stdout[-3000:]}\n"
                 f"{r.stderr[-3000:]}")
    return r.stdout


def projection_error(frame):
    """Largest distance, pixels, between where position projects and pixel centre + jitter."""
    p = frame["position"]
    h, w, _ = p.shape
    clip = np.concatenate([p, np.ones((h, w, 1), np.float32)], -1) @ frame["view_projection"].T
    u = (clip[..., 0] / clip[..., 3] * 0.5 + 0.5) * w
    v = (clip[..., 1] / clip[..., 3] * 0.5 + 0.5) * h
    ys, xs = np.mgrid[0:h, 0:w]
    jx, jy = frame["jitter"]
    return float(max(np.abs(u - (xs + 0.5 + jx)).max(), np.abs(v - (ys + 0.5 + jy)).max()))


def main():
    if not BLENDER:
        print("blender is not installed: skipped")
        return 77
    work = tempfile.mkdtemp(prefix="bmfr_blender_")
    blend, seq = os.path.join(work, "room.blend"), os.path.join(work, "seq")
    run(BLENDER, "-b", "--factory-startup", "--python",
        os.path.join(ROOT, "tools/blender/make_test_scene.py"), "--", blend)
    run(BLENDER, "-b", blend, "--python", os.path.join(ROOT, "tools/blender/render_sequence.py"),
        "--", seq, "--width", 32, "--height", 18, "--reference-spp", 64, "-q")

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
        run(CLI, "denoise", seq, "-o", out, "--filter", name, "--no-png", "-q")
        report = json.load(open(os.path.join(out, "report.json")))
        scores[name] = report["scores"]
    table = json.loads(run(CLI, "eval", "-r", seq, "-m", "noisy", "-m",
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
