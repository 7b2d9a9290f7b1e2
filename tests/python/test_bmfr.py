"""The Python module against the C++ CLI: the same frames give the same bits; bad arguments raise
TypeError or ValueError naming the argument, library errors bmfr.Error; reset drops the history;
the GIL is free while denoising."""
import os
import subprocess
import threading

import numpy as np
import pytest

import bmfr

CLI = os.environ.get("BMFR_CLI", "bmfr")


def cli(*args):
    subprocess.run([CLI, *map(str, args)], check=True, capture_output=True)


@pytest.fixture(scope="module")
def sequence(tmp_path_factory):
    path = tmp_path_factory.mktemp("seq")
    cli("synth", "-o", path, "--width", 48, "--height", 32, "--frames", 5, "-q")
    return path


def sequence_settings(info):
    """What `bmfr denoise` takes from a sequence: its own discard limits and demodulation flag."""
    s = {}
    if info["position_limit_squared"] is not None:
        s["position_limit"] = info["position_limit_squared"]
    if info["normal_limit_squared"] is not None:
        s["normal_limit"] = info["normal_limit_squared"]
    if info["color_is_demodulated"]:
        s["color_is_demodulated"] = True
    return s


def frame_args(fr):
    return (fr["color"], fr["albedo"], fr["normal"], fr["position"], fr["view_projection"])


@pytest.mark.parametrize("name,extra", [("bmfr", []), ("svgf", []), ("walr", []), ("mara2017", []),
                                         ("bmfr", ["--block-size", 16, "--taa", "false"]),
                                         ("bmfr", ["--features", "1,n.x,n.y,n.z,extra0"])])
def test_same_bits_as_the_cli(sequence, tmp_path, name, extra):
    cli("denoise", sequence, "-o", tmp_path, "--filter", name, "--no-png", "--no-flip", "-q",
        *extra)
    seq = bmfr.read_sequence(str(sequence))
    settings = sequence_settings(seq.info)
    for flag, value in zip(extra[::2], extra[1::2]):
        settings[flag.lstrip("-").replace("-", "_")] = value
    f = bmfr.Filter(name, **settings)
    count = 0
    for fr in seq:
        out = f.denoise(*frame_args(fr), jitter=fr["jitter"], emission=fr.get("emission"),
                        extras=fr["extras"], visibility=fr.get("visibility"))
        expected = bmfr.read_exr(str(tmp_path / f"denoised_{fr['index']:04d}.exr"))
        assert out.shape == (32, 48, 3) and out.dtype == np.float32
        assert np.array_equal(out, expected), f"frame {fr['index']} differs from the CLI"
        count += 1
    assert count == len(seq) == 5
    assert f.stats["total_ms"] > 0 and "non_finite_inputs" in f.stats


def test_the_faithful_preset_gives_the_cli_bits(sequence, tmp_path):
    cli("denoise", sequence, "-o", tmp_path, "--preset", "faithful", "--no-png", "--no-flip", "-q")
    assert bmfr.preset("bmfr", "faithful") == {
        "taa_same_surface": "false", "taa_range_compressed": "false",
        "taa_motion_weight": "false", "exclude_emitters": "false",
        "second_grid": "false", "clamp_fireflies": "false", "visibility_feature": "false",
        "visibility_taps": "false", "block_size": "32", "emitter_ratio": "16",
        "adaptive_history": "false", "alpha2": "0.1", "noise": "0.01"}
    assert bmfr.preset("bmfr", "quality") == {}
    with pytest.raises(ValueError, match="unknown preset 'fast'"):
        bmfr.preset("bmfr", "fast")
    with pytest.raises(ValueError, match="preset: unknown preset 'fast'"):
        bmfr.Filter("bmfr", preset="fast")
    seq = bmfr.read_sequence(str(sequence))
    f = bmfr.Filter("bmfr", preset="faithful", **sequence_settings(seq.info))
    for fr in seq:
        out = f.denoise(*frame_args(fr), jitter=fr["jitter"], emission=fr.get("emission"),
                        extras=fr["extras"], visibility=fr.get("visibility"))
        expected = bmfr.read_exr(str(tmp_path / f"denoised_{fr['index']:04d}.exr"))
        assert np.array_equal(out, expected), f"frame {fr['index']} differs from the CLI"


def test_rgba_and_padded_rows_give_the_same_result(sequence):
    fr = next(iter(bmfr.read_sequence(str(sequence))))
    packed = bmfr.Filter().denoise(*frame_args(fr))
    h, w, _ = fr["color"].shape
    rgba = np.zeros((h, w, 4), np.float32)
    rgba[..., :3] = fr["color"]
    wide = np.zeros((h, w + 7, 3), np.float32)  # rows padded: a view, not a copy
    wide[:, :w] = fr["albedo"]
    strided = np.ascontiguousarray(fr["normal"][:, ::-1])[:, ::-1]  # negative strides: a copy
    out = bmfr.Filter().denoise(rgba, wide[:, :w], strided, fr["position"], fr["view_projection"])
    assert np.array_equal(out, packed)


def test_bad_arguments_raise_type_or_value_errors_naming_them(sequence):
    fr = next(iter(bmfr.read_sequence(str(sequence))))
    c, a, n, p, vp = frame_args(fr)
    f = bmfr.Filter()
    cases = [
        ((c.astype(np.float64), a, n, p, vp), ValueError, "color: dtype float64"),
        ((c, a[:, :, :2], n, p, vp), ValueError, "albedo: shape (32, 48, 2)"),
        ((c, a, n[:16], p, vp), ValueError, "normal: shape (16, 48, 3), the colour is 32x48"),
        ((c, a, n, p[..., 0], vp), ValueError, "position: shape (32, 48)"),
        ((c, a, n, [[1, 2, 3]], vp), TypeError, "position: expected a numpy array, got list"),
        ((c, a, n, p, np.eye(3)), ValueError, "view_projection: expected a 4x4 matrix"),
        ((c, a, n, p, np.zeros((4, 4))), bmfr.Error, "not finite or not invertible"),
        ((c[:0], a[:0], n[:0], p[:0], vp), ValueError, "color: empty image"),
        ((c, a, n, p), TypeError, "denoise() missing required argument 'view_projection'"),
        ((c, a, n), TypeError, "denoise() missing required argument 'position'"),
    ]
    for args, kind, message in cases:
        with pytest.raises(kind) as e:
            f.denoise(*args)
        assert message in str(e.value)
        assert len(str(e.value)) < 300, "a long message: " + str(e.value)[:300]
    with pytest.raises(ValueError, match="emission: shape"):
        f.denoise(c, a, n, p, vp, emission=c[:8])
    with pytest.raises(ValueError, match=r"extras\[0\]: shape \(32, 48, 3\)"):
        f.denoise(c, a, n, p, vp, extras=[c])
    with pytest.raises(TypeError, match="extras: expected a list"):
        f.denoise(c, a, n, p, vp, extras=c[..., 0])
    with pytest.raises(TypeError, match=r"^denoise\(\) got an unexpected argument 'emision' "
                                        r"\(the buffers: color, albedo"):
        f.denoise(c, a, n, p, vp, emision=c)
    with pytest.raises(ValueError, match=r"sample_mask: shape \(32, 47\)"):
        f.denoise(c, a, n, p, vp, sample_mask=c[:, :47, 0])
    with pytest.raises(TypeError, match="got multiple values for argument 'color'"):
        f.denoise(c, a, n, p, vp, color=c)


def test_input_buffers_are_the_frame_buffer_table(sequence):
    names = bmfr.input_buffers()
    assert names[:4] == ["color", "albedo", "normal", "position"]
    assert len(names) == len(set(names)) == 17
    fr = next(iter(bmfr.read_sequence(str(sequence))))
    # Every buffer a frame of the sequence carries goes back into denoise by the same keyword.
    optional = {k: fr[k] for k in names[4:] if k in fr}
    assert "visibility" in optional  # the synthetic sequence has one
    out = bmfr.Filter().denoise(*frame_args(fr), jitter=fr["jitter"], **optional)
    assert out.shape == fr["color"].shape


def test_settings_errors_are_setting_errors_with_the_python_name():
    with pytest.raises(bmfr.SettingError, match=r"^block_size 7 is outside \[8, 64\]$") as e:
        bmfr.Filter("bmfr", block_size=7)
    assert (e.value.key, e.value.name, e.value.value, e.value.problem) == (
        "blockSize", "block_size", "7", "is outside [8, 64]")
    assert isinstance(e.value, bmfr.Error)
    with pytest.raises(bmfr.SettingError, match="block_size x is not"):
        bmfr.Filter("bmfr", blockSize="x")
    with pytest.raises(TypeError, match="no_such is not a setting of the bmfr filter"):
        bmfr.Filter("bmfr", no_such=1)
    with pytest.raises(ValueError, match="name: unknown filter 'nope'"):
        bmfr.Filter("nope")
    with pytest.raises(TypeError, match="taa: expected a bool"):
        bmfr.Filter("bmfr", taa=[1])
    assert bmfr.Filter("svgf", svgf_iterations=3, taa=False).name == "svgf"
    assert {s["name"] for s in bmfr.settings("bmfr")} >= {"block_size", "taa", "backend"}


def test_reset_drops_the_history(sequence):
    frames = list(bmfr.read_sequence(str(sequence)))
    f = bmfr.Filter()
    for fr in frames[:3]:
        f.denoise(*frame_args(fr))
    f.reset()
    after_reset = f.denoise(*frame_args(frames[3]))
    fresh = bmfr.Filter().denoise(*frame_args(frames[3]))
    assert np.array_equal(after_reset, fresh)
    f.denoise(*frame_args(frames[0]))
    assert np.array_equal(f.denoise(*frame_args(frames[3]), reset=True), fresh)
    assert not np.array_equal(bmfr.Filter().denoise(*frame_args(frames[2])), frames[2]["color"])


def test_the_gil_is_released_while_denoising():
    """Another Python thread runs while a frame is denoised on the slow reference backend."""
    h, w = 360, 640
    rng = np.random.default_rng(1)
    color = rng.random((h, w, 3), dtype=np.float32)
    albedo = np.full((h, w, 3), 0.5, np.float32)
    normal = np.zeros((h, w, 3), np.float32)
    normal[..., 2] = 1
    ys, xs = np.mgrid[0:h, 0:w].astype(np.float32)
    position = np.stack([xs / w - 0.5, ys / h - 0.5, np.full_like(xs, -2)], axis=-1)
    vp = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, -1, -0.2], [0, 0, -1, 0]], np.float32)
    f = bmfr.Filter("bmfr", backend="reference", threads=1)
    done = threading.Event()
    ticks = 0

    def work():
        f.denoise(color, albedo, normal, position, vp)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    while not done.is_set():
        ticks += 1
        done.wait(0.001)
    t.join()
    assert ticks > 5, "the main thread did not run while the frame was denoised"


def test_read_sequence_errors_and_exr_round_trip(sequence, tmp_path):
    with pytest.raises(bmfr.Error, match="not found"):
        bmfr.read_sequence(str(tmp_path / "missing"))
    fr = next(iter(bmfr.read_sequence(str(sequence))))
    assert set(fr) >= {"index", "color", "albedo", "normal", "position", "view_projection",
                       "jitter", "reference", "extras"}
    assert fr["view_projection"].shape == (4, 4)
    assert issubclass(bmfr.SettingError, bmfr.Error) and not issubclass(bmfr.Error, ValueError)


@pytest.mark.parametrize("name,settings", [("bmfr", {}),
                                           ("walr", {"walr_signal": "diffuse-indirect"})])
def test_motion_vectors_give_the_cli_bits_on_moving_objects(tmp_path, name, settings):
    seq_dir = tmp_path / "objects"
    cli("render", "-s", "cornell-objects", "--width", 40, "--height", 30, "--frames", 4,
        "--no-reference", "-q", "-o", seq_dir)
    flags = [a for k, v in settings.items() for a in ("--" + k.replace("_", "-"), v)]
    cli("denoise", seq_dir, "-o", tmp_path / "cli", "--no-png", "-q", "--filter", name, *flags)
    seq = bmfr.read_sequence(str(seq_dir))
    f = bmfr.Filter(name, **sequence_settings(seq.info), **settings)
    for fr in seq:
        # Motion carries the depth offset as its third channel.
        assert fr["motion"].shape == (30, 40, 3) and fr["previous_position"].shape == (30, 40, 3)
        out = f.denoise(*frame_args(fr), jitter=fr["jitter"], emission=fr.get("emission"),
                        extras=fr["extras"], motion=fr["motion"],
                        previous_position=fr["previous_position"],
                        previous_normal=fr["previous_normal"], reset=fr["reset"],
                        diffuse_indirect=fr["diffuse_indirect"])
        expected = bmfr.read_exr(str(tmp_path / "cli" / f"denoised_{fr['index']:04d}.exr"))
        assert np.array_equal(out, expected), f"frame {fr['index']} differs from the CLI"
    with pytest.raises(ValueError, match=r"motion: shape \(30, 40, 1\), expected \(height, "
                                         r"width, C\) with C 2 to 4"):
        f.denoise(*frame_args(fr), motion=np.zeros((30, 40, 1), np.float32))


MARA_BUFFERS = ("matte_indirect", "glossy_indirect", "direct_light", "specular_f0", "roughness",
                "glossy_hit_distance")


def test_mara_factorisation_gives_the_cli_bits(tmp_path):
    seq_dir = tmp_path / "mara"
    cli("render", "-s", "cornell-moving", "--width", 40, "--height", 30, "--frames", 3,
        "--no-reference", "-q", "--paths", "mara", "--direct-spp", 2, "-o", seq_dir)
    cli("denoise", seq_dir, "-o", tmp_path / "cli", "--no-png", "-q", "--filter", "mara2017")
    seq = bmfr.read_sequence(str(seq_dir))
    f = bmfr.Filter("mara2017", **sequence_settings(seq.info))
    for fr in seq:
        assert fr["roughness"].shape == (30, 40, 1) and fr["matte_indirect"].shape == (30, 40, 3)
        out = f.denoise(*frame_args(fr), jitter=fr["jitter"], emission=fr.get("emission"),
                        **{k: fr[k] for k in MARA_BUFFERS})
        expected = bmfr.read_exr(str(tmp_path / "cli" / f"denoised_{fr['index']:04d}.exr"))
        assert np.array_equal(out, expected), f"frame {fr['index']} differs from the CLI"
    with pytest.raises(ValueError, match="roughness"):
        f.denoise(*frame_args(fr), roughness=np.zeros((30, 41), np.float32))
