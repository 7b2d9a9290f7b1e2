"""The Blender render script's sun visibility pass against shadow rays cast here.

A floor, a floating cube and a plane whose alpha is a checker, lit by a sun (and a point
light the pass must leave out), rendered by tools/blender/render_sequence.py. For every pixel
the test casts a ray from the pixel's Position towards the sun against the cube (slab test) and
the plane (its checker square at the crossing), and takes the cosine with the Normal: the pass
must equal that, to float rounding, at all but the pixels whose shadow ray passes within a
hair of an edge. The jitter of the two frames is on, so the pass must follow it; the sun is
coloured and its strength animated, which the pass must not follow; and the scene must be as
it was afterwards (visibility_driver.py). Exit 77 (skipped) without Blender."""
import json
import os
import shutil
import sys
import tempfile

import numpy as np

import bmfr

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../tools/blender"))
import blender_run  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def in_shadow(p, d, geo):
    """Whether the ray p + t d, t > 0, hits the cube or an opaque square of the plane."""
    c, h = np.array(geo["cube"][0]), geo["cube"][1]
    with np.errstate(divide="ignore", invalid="ignore"):
        t0 = (c - h - p) / d
        t1 = (c + h - p) / d
    near = np.minimum(t0, t1).max(axis=-1)
    far = np.maximum(t0, t1).min(axis=-1)
    cube = (far >= np.maximum(near, 1e-4))
    lc, lh = np.array(geo["leaf"][0]), geo["leaf"][1]
    t = (lc[2] - p[..., 2]) / d[..., 2]
    x = p + t[..., None] * d
    u = (x[..., 0] - (lc[0] - lh)) / (2 * lh)
    v = (x[..., 1] - (lc[1] - lh)) / (2 * lh)
    inside = (t > 1e-4) & (u >= 0) & (u < 1) & (v >= 0) & (v < 1)
    # Blender's checker at scale 4 over the plane's UV square: squares of 1/4, white (alpha 1)
    # where floor(4u) + floor(4v) is even... measured from the texture coordinate, which for a
    # plane primitive is its UV, 0..1 over the plane.
    opaque = (np.floor(4 * u + 1e-6) + np.floor(4 * v + 1e-6)) % 2 == 0
    return cube, inside & opaque, inside & ~opaque


def edge_distance(p, d, geo):
    """How close, in scene units, the ray passes to the plane's square borders (for the pixels
    left out)."""
    lc, lh = np.array(geo["leaf"][0]), geo["leaf"][1]
    t = (lc[2] - p[..., 2]) / d[..., 2]
    x = p + t[..., None] * d
    s = 2 * lh / 4
    du = np.abs((x[..., 0] - (lc[0] - lh)) / s - np.round((x[..., 0] - (lc[0] - lh)) / s)) * s
    dv = np.abs((x[..., 1] - (lc[1] - lh)) / s - np.round((x[..., 1] - (lc[1] - lh)) / s)) * s
    return np.minimum(du, dv)


def main():
    blender_run.require_blender()
    work = tempfile.mkdtemp(prefix="bmfr_visibility_")
    blend, seq = os.path.join(work, "sun.blend"), os.path.join(work, "seq")
    blender_run.run_script(os.path.join(HERE, "sun_scene.py"), blend)
    # Rendered in Blender by the add-on's module, which then checks the scene was put back.
    out = blender_run.run_script(os.path.join(HERE, "visibility_driver.py"), blend, seq)
    assert "scene restored" in out, out[-2000:]
    geo = json.load(open(blend + ".json"))
    d = np.array(geo["sun_towards"], dtype=np.float64)
    d /= np.linalg.norm(d)
    frames = list(bmfr.read_sequence(seq))
    assert len(frames) == 2
    for f in frames:
        vis = f["visibility"][..., 0] if f["visibility"].ndim == 3 else f["visibility"]
        p = f["position"].astype(np.float64)
        n = f["normal"].astype(np.float64)
        n /= np.linalg.norm(n, axis=-1, keepdims=True)
        cos = np.clip((n * d).sum(-1), 0, None)
        dd = np.broadcast_to(d, p.shape)
        cube, leaf, through = in_shadow(p, dd, geo)
        expected = np.where(cube | leaf, 0.0, cos)
        bad = np.abs(vis - expected) > 2e-3
        # Rays that graze a square's border or the cube's edge may go either way.
        near_edge = edge_distance(p, dd, geo) < 2e-3
        wrong = bad & ~near_edge
        lit = (expected > 0).mean()
        print(f"frame {f['index']}: jitter {f['jitter']}, lit {lit:.2f}, in the cube's shadow "
              f"{(cube & (cos > 0)).sum()} px, the leaf's {(leaf & (cos > 0)).sum()} px, through "
              f"its clear squares {(through & ~cube & (cos > 0)).sum()} px; differing "
              f"{bad.sum()} px, of them not at an edge {wrong.sum()}, max |diff| elsewhere "
              f"{np.abs(vis - expected)[~near_edge].max():.2e}")
        for what, mask in (("cube's shadow", cube), ("leaf's shadow", leaf),
                           ("leaf's clear squares", through & ~cube)):
            assert (mask & (cos > 0)).sum() >= 20, f"too few pixels in the {what} to test"
        assert wrong.sum() <= 3, f"{wrong.sum()} pixels differ from the shadow rays"
    doc = json.load(open(os.path.join(seq, "sequence.json")))
    assert "visibility of the sun 'sun'" in doc["generator"], doc["generator"]
    shutil.rmtree(work)
    print("blender visibility test passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
