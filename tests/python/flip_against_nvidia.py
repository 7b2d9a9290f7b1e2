"""bmfr's FLIP (bmfr.flip, the metric `bmfr eval` reports) against NVIDIA's own implementation
(PyPI flip-evaluator, NVlabs/flip): the mean and every pixel of the error map agree to 1e-4 on
LDR pairs of sizes that are not multiples of anything, flat and textured.
Usage: flip_against_nvidia.py (with bmfr and flip_evaluator importable)"""
import sys

import numpy as np

import bmfr
import flip_evaluator

TOLERANCE = 1e-4
PPD = 0.7 * (3840 / 0.7) * np.pi / 180  # NVIDIA's default viewing condition


def pairs():
    """(name, reference, test): float32 (H, W, 3) sRGB values in [0, 1]."""
    rng = np.random.default_rng(52)
    for h, w in [(23, 37), (48, 64), (67, 101), (1, 9)]:
        flat = np.full((h, w, 3), 0.5, np.float32)
        yield f"flat {w}x{h} vs a brighter flat", flat, np.full_like(flat, 0.6)
        texture = rng.random((h, w, 3), dtype=np.float32)
        noisy = np.clip(texture + rng.normal(0, 0.08, texture.shape), 0, 1).astype(np.float32)
        yield f"texture {w}x{h} vs noise", texture, noisy
        yy, xx = np.mgrid[0:h, 0:w]
        edges = (((xx // 4 + yy // 3) % 2)[..., None] * np.array([0.9, 0.2, 0.1])).astype(np.float32)
        yield f"checker {w}x{h} vs shifted", edges, np.roll(edges, 1, axis=1)
    red = np.zeros((16, 16, 3), np.float32)
    red[..., 0] = 1
    yield "identical", red, red.copy()


def main():
    worst = 0.0
    failures = []
    for name, ref, test in pairs():
        nv_map, nv_mean, _ = flip_evaluator.evaluate(ref, test, "LDR", inputsRGB=True,
                                                     applyMagma=False, computeMeanError=True,
                                                     parameters={"ppd": PPD})
        mean, ours = bmfr.flip(ref, test, ppd=PPD)
        nv_map = np.asarray(nv_map, np.float64).reshape(ref.shape[0], ref.shape[1])
        ours = np.asarray(ours, np.float64)[..., 0]
        pixel = float(np.max(np.abs(nv_map - ours)))
        worst = max(worst, pixel, abs(mean - nv_mean))
        line = (f"{name:34s} NVIDIA mean {nv_mean:.6f}  bmfr {mean:.6f}  "
                f"largest pixel difference {pixel:.2e}")
        print(line)
        if abs(mean - nv_mean) > TOLERANCE or pixel > TOLERANCE:
            failures.append(line)
    print(f"largest difference over all pairs: {worst:.2e} (tolerance {TOLERANCE})")
    if failures:
        print("FAILED:\n" + "\n".join(failures))
        return 1
    print("flip against nvidia passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
