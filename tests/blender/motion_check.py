"""Cycles' vectors against the positions they must have been at.

For a sequence rendered by tools/blender/render_sequence.py from the scene of
tools/blender/make_test_scene.py (a sphere moving at a known constant velocity, a panning
camera): each pixel's previous world position is, by hand, its Position minus the sphere's
velocity where the pixel is on the sphere (|P - centre| = radius) and its Position elsewhere
(the room is static). bmfr's motion (as `bmfr denoise` reads it, Cycles' Vector converted) must
take the pixel to where that point projects through the previous frame's view-projection, as a
continuous coordinate whose integers are the previous frame's sample positions (pixel centre
plus its jitter); the previous_position buffer must be that point.

    motion_check.py SEQUENCE SCENE_JSON  -> prints the largest errors, exits 1 beyond the bounds
"""
import json
import os
import sys

import numpy as np

import bmfr

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../tools/blender"))
import sphere_path  # noqa: E402

MOTION_BOUND_PX = 0.02
POSITION_BOUND = 1e-3  # scene units (the room is 2 units wide)


def project(vp, p, w, h, jitter):
    """Continuous pixel coordinate of world points p (..., 3): integers at sample positions."""
    clip = np.concatenate([p, np.ones(p.shape[:-1] + (1,), np.float64)], -1) @ np.asarray(vp).T
    u = (clip[..., 0] / clip[..., 3] * 0.5 + 0.5) * w - 0.5 - jitter[0]
    v = (clip[..., 1] / clip[..., 3] * 0.5 + 0.5) * h - 0.5 - jitter[1]
    return u, v


def check(seq, scene_json):
    path = json.load(open(scene_json))["sphere"]
    vel = sphere_path.velocity(path)
    frames = list(bmfr.read_sequence(seq))
    doc = json.load(open(f"{seq}/sequence.json"))
    assert doc.get("motion_convention") == "cycles", "no motion written"
    worst_motion = worst_prev = 0.0
    sphere_pixels = 0
    for k in range(1, len(frames)):
        f, prev = frames[k], frames[k - 1]
        p = f["position"].astype(np.float64)
        h, w, _ = p.shape
        on = sphere_path.on_sphere(p, path, sphere_path.blender_frame(doc["frames"][k]))
        sphere_pixels += int(on.sum())
        expected = p - np.where(on[..., None], vel, 0.0)
        u, v = project(prev["view_projection"], expected, w, h, prev["jitter"])
        ys, xs = np.mgrid[0:h, 0:w]
        m = f["motion"].astype(np.float64)
        err = np.maximum(np.abs(xs + m[..., 0] - u), np.abs(ys + m[..., 1] - v))
        worst_motion = max(worst_motion, float(err.max()))
        perr = np.abs(f["previous_position"].astype(np.float64) - expected).max(-1)
        worst_prev = max(worst_prev, float(perr.max()))
        print(f"frame {k}: {int(on.sum())} sphere pixels; motion error max {err.max():.5f} px "
              f"(sphere {err[on].max() if on.any() else 0:.5f}); previous position error max "
              f"{perr.max():.2e}")
    print(f"largest motion error {worst_motion:.5f} px (bound {MOTION_BOUND_PX}), largest "
          f"previous position error {worst_prev:.2e} (bound {POSITION_BOUND}), "
          f"{sphere_pixels} sphere pixels")
    assert sphere_pixels > 0, "the sphere is not in view"
    assert worst_motion < MOTION_BOUND_PX, worst_motion
    assert worst_prev < POSITION_BOUND, worst_prev


if __name__ == "__main__":
    check(sys.argv[1], sys.argv[2])
    print("motion check passed")
