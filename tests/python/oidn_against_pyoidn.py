"""`bmfr peer oidn` against OIDN driven through its own Python binding (PyPI pyoidn, OIDN's
library in the same wheel), for each --prefilter as Blender defines it: none passes albedo and
normal as noise free (cleanAux), fast passes them as possibly noisy, accurate denoises each of
them with an RT filter of its own first and then passes them as noise free. Every frame the peer
wrote must match pyoidn's to 1e-4 (largest absolute difference over the frame's largest value),
and the peer must cut the noisy input's error against the reference by a third or more.
Usage: oidn_against_pyoidn.py SEQUENCE PEER_OUTPUTS (PEER_OUTPUTS/PREFILTER/denoised_NNNN.exr;
bmfr and pyoidn importable)"""
import os
import sys

import numpy as np
import pyoidn

import bmfr

TOLERANCE = 1e-4


def prefiltered(device, image, name):
    """The RT filter on an auxiliary image alone, as OIDN's documentation prefilters one."""
    out = np.empty_like(image)
    flt = pyoidn.Filter(device, pyoidn.OIDN_FILTER_TYPE_RT)
    flt.set_image(name, image, pyoidn.OIDN_FORMAT_FLOAT3)
    flt.set_image(pyoidn.OIDN_IMAGE_OUTPUT, out, pyoidn.OIDN_FORMAT_FLOAT3)
    flt.set_quality(pyoidn.OIDN_QUALITY_HIGH)
    flt.commit()
    flt.execute()
    flt.release()
    return out


def expected(device, frame, prefilter, demodulated):
    color = np.ascontiguousarray(frame["color"][..., :3], np.float32)
    albedo = np.ascontiguousarray(frame["albedo"][..., :3], np.float32)
    normal = np.ascontiguousarray(frame["normal"][..., :3], np.float32)
    if demodulated:
        color = color * albedo
    if prefilter == "accurate":
        albedo = prefiltered(device, albedo, pyoidn.OIDN_IMAGE_ALBEDO)
        normal = prefiltered(device, normal, pyoidn.OIDN_IMAGE_NORMAL)
    return pyoidn.denoise(color, albedo, normal, hdr=True, clean_aux=prefilter != "fast",
                          quality="high")


def tone(x):
    return np.clip(np.maximum(x, 0) ** (1 / 2.2), 0, 1)


def main():
    seq_dir, outputs = sys.argv[1], sys.argv[2]
    sequence = bmfr.read_sequence(seq_dir)
    demodulated = bool(sequence.settings.get("color_is_demodulated", False))
    device = pyoidn.Device(pyoidn.OIDN_DEVICE_TYPE_CPU)
    device.commit()
    failures = 0
    for prefilter in ("none", "fast", "accurate"):
        worst, noisy_err, peer_err = 0.0, 0.0, 0.0
        for frame in sequence:
            i = frame["index"]
            path = os.path.join(outputs, prefilter, f"denoised_{i:04d}.exr")
            peer = bmfr.read_exr(path)
            want = expected(device, frame, prefilter, demodulated)
            scale = max(float(np.abs(want).max()), 1e-6)
            worst = max(worst, float(np.abs(peer - want).max()) / scale)
            ref = tone(frame["reference"][..., :3])
            noisy = frame["color"][..., :3] * (frame["albedo"][..., :3] if demodulated else 1)
            noisy_err += float(np.sqrt(np.mean((tone(noisy) - ref) ** 2)))
            peer_err += float(np.sqrt(np.mean((tone(peer) - ref) ** 2)))
        ok = worst <= TOLERANCE and peer_err <= 2 / 3 * noisy_err
        failures += not ok
        print(f"{'ok  ' if ok else 'FAIL'} prefilter {prefilter}: largest difference from pyoidn "
              f"{worst:.2e} of the frame's peak (<= {TOLERANCE:g}); RMSE {peer_err:.4f} against "
              f"the noisy input's {noisy_err:.4f} (summed over frames)")
    device.release()
    if failures:
        sys.exit(1)
    print("oidn against pyoidn passed")


if __name__ == "__main__":
    main()
