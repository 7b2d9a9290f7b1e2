"""The Python API a numpy user expects: frames from read_sequence go back in whole (motion
included), out=, write_exr, indexable sequences, presets and devices, the inputs a filter reads
and a warning for a missing one, bmfr.Error for every library error, and the documented example
giving the CLI's bits."""
import os
import shutil
import subprocess
import sys
import warnings

import numpy as np
import pytest

import bmfr

CLI = os.environ.get("BMFR_CLI", "bmfr")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def cli(*args):
    subprocess.run([CLI, *map(str, args)], check=True, capture_output=True)


@pytest.fixture(scope="module")
def objects(tmp_path_factory):
    """Moving objects: every frame carries motion vectors and previous positions."""
    path = tmp_path_factory.mktemp("objects")
    cli("render", "-s", "cornell-objects", "--width", 40, "--height", 30, "--frames", 5,
        "--reference-spp", 4, "-q", "-o", path)
    return path


@pytest.fixture(scope="module")
def cli_result(objects, tmp_path_factory):
    out = tmp_path_factory.mktemp("cli")
    cli("denoise", objects, "-o", out, "--no-png", "--no-flip", "-q")
    return out


def cli_frame(cli_result, i):
    return bmfr.read_exr(str(cli_result / f"denoised_{i:04d}.exr"))


def test_whole_frames_go_back_in_with_their_motion(objects, cli_result):
    seq = bmfr.read_sequence(str(objects))
    assert "motion" in seq[0] and "previous_position" in seq[0]
    by_frame, by_keywords = bmfr.Filter(**seq.settings), bmfr.Filter(**seq.settings)
    for frame in seq:
        a = by_frame.denoise_frame(frame)
        b = by_keywords.denoise(**frame)  # index and reference are accepted and not used
        assert np.array_equal(a, b)
        assert np.array_equal(a, cli_frame(cli_result, frame["index"])), frame["index"]
    # The camera alone differs: the motion vectors were used.
    plain = bmfr.Filter(**seq.settings)
    for frame in seq:
        without = plain.denoise(frame["color"], frame["albedo"], frame["normal"],
                                frame["position"], frame["view_projection"], frame["jitter"])
    assert not np.array_equal(without, a)


def test_the_documented_example_gives_the_cli_bits(objects, cli_result, tmp_path):
    example = os.path.join(ROOT, "examples", "python", "denoise_sequence.py")
    with open(example) as f:
        code = f.read()
    with open(os.path.join(ROOT, "docs", "python.md")) as f:
        assert code.strip() in f.read(), "docs/python.md does not show the example as it is"
    out = tmp_path / "py"
    subprocess.run([sys.executable, example, str(objects), str(out)], check=True,
                   capture_output=True)
    for i in range(5):
        assert np.array_equal(bmfr.read_exr(str(out / f"denoised_{i:04d}.exr")),
                              cli_frame(cli_result, i)), i


def test_short_errors_for_argument_mistakes(objects):
    frame = bmfr.read_sequence(str(objects))[0]
    f = bmfr.Filter()
    with pytest.raises(ValueError) as e:
        f.denoise(**{**frame, "jitter": (0, 0, 0)})
    assert str(e.value).startswith("jitter: expected two numbers (x, y), pixels, got (0, 0, 0)")
    with pytest.raises(TypeError) as e:
        f.denoise(frame["color"], frame["albedo"], frame["normal"])
    assert "array(" not in str(e.value) and len(str(e.value)) < 200, str(e.value)[:300]
    with pytest.raises(TypeError, match="at most 6 positional arguments"):
        f.denoise(*[frame["color"]] * 7)


def test_out_writes_in_place(objects):
    seq = bmfr.read_sequence(str(objects))
    expected = bmfr.Filter().denoise_frame(seq[0])
    out = np.full((30, 40, 4), 7.0, np.float32)
    result = bmfr.Filter().denoise_frame(seq[0], out=out)
    assert result is out
    assert np.array_equal(out[..., :3], expected) and np.all(out[..., 3] == 7.0)
    with pytest.raises(ValueError, match=r"out: shape \(30, 41, 3\)"):
        bmfr.Filter().denoise_frame(seq[0], out=np.zeros((30, 41, 3), np.float32))
    with pytest.raises(ValueError, match="out: its pixels must be packed"):
        bmfr.Filter().denoise_frame(seq[0], out=np.zeros((40, 30, 3), np.float32).transpose(1, 0, 2))


def test_sequences_index_and_slice(objects):
    seq = bmfr.read_sequence(str(objects))
    assert len(seq) == 5 and seq[-1]["index"] == 4 and seq[2]["index"] == 2
    part = seq[1:4]
    assert len(part) == 3 and [f["index"] for f in part] == [1, 2, 3]
    assert [f["index"] for f in seq[::2]] == [0, 2, 4] and part[-1]["index"] == 3
    assert np.array_equal(seq[3]["color"], list(seq)[3]["color"])
    with pytest.raises(IndexError, match="frame 5 is outside a sequence of 5 frames"):
        seq[5]
    with pytest.raises(TypeError):
        seq["a"]
    assert "5 of 5 frames, 40x30" in repr(seq)


def test_exr_files_in_and_out(tmp_path):
    for shape in [(6, 5), (6, 5, 1), (6, 5, 2), (6, 5, 3)]:
        image = np.random.default_rng(1).random(shape, dtype=np.float32)
        path = str(tmp_path / f"x{len(shape)}.exr")
        bmfr.write_exr(path, image)
        channels = 1 if len(shape) == 2 else shape[2]
        back = bmfr.read_exr(path, channels=channels)
        assert np.array_equal(back.reshape(image.shape), image)
    with pytest.raises(ValueError, match="image: dtype float64"):
        bmfr.write_exr(str(tmp_path / "y.exr"), np.zeros((4, 4, 3)))
    with pytest.raises(TypeError, match="image: expected a numpy array"):
        bmfr.write_exr(str(tmp_path / "y.exr"), [[1.0]])
    cycles = os.path.join(ROOT, "tests", "data", "cycles_denoiser_on.exr")
    assert "ViewLayer.Noisy Image.R" in bmfr.exr_channels(cycles)
    noisy = bmfr.read_exr(cycles, layer="ViewLayer.Noisy Image")
    denoised = bmfr.read_exr(cycles, layer="ViewLayer.Combined")
    assert noisy.shape == (16, 24, 3) and not np.array_equal(noisy, denoised)


def test_presets_devices_and_repr(objects):
    f = bmfr.Filter("bmfr", preset="faithful", block_size=16, taa=False)
    assert repr(f) == "bmfr.Filter('bmfr', preset='faithful', backend='cpu', block_size=16, taa=False)"
    device = bmfr.Device("cpu", threads=2)
    assert repr(device) == "bmfr.Device(backend='cpu', threads=2)"
    device.reserve(40, 30)
    frame = bmfr.read_sequence(str(objects))[0]
    on_device = bmfr.Filter("svgf", device=device).denoise_frame(frame)
    assert np.array_equal(on_device, bmfr.Filter("svgf", threads=2).denoise_frame(frame))
    with pytest.raises(TypeError, match="backend= or device=, not both"):
        bmfr.Filter("svgf", backend="cpu", device=device)
    with pytest.raises(bmfr.Error, match="cudaDevice 1 is the cuda backend's"):
        bmfr.Device("cpu", cuda_device=1)


def test_inputs_and_a_warning_for_a_missing_one(objects):
    assert bmfr.Filter("bmfr").inputs[:4] == ["color", "albedo", "normal", "position"]
    assert "visibility" in bmfr.Filter("bmfr").inputs
    assert "visibility" not in bmfr.Filter("bmfr", preset="faithful").inputs
    assert "sample_mask" in bmfr.Filter("svgf").inputs
    assert "matte_indirect" in bmfr.Filter("mara2017").inputs
    assert "diffuse_indirect" in bmfr.Filter("walr", walr_signal="diffuse-indirect").inputs
    frame = bmfr.read_sequence(str(objects))[0]
    mara = bmfr.Filter("mara2017")
    with pytest.warns(UserWarning, match="mara2017: the frame has no matte_indirect") as caught:
        mara.denoise_frame(frame)
        mara.denoise_frame(frame)  # once per filter
    assert len(caught) == 1 and caught[0].filename == __file__
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        bmfr.Filter("bmfr").denoise_frame(frame)  # nothing it is designed around is missing


def test_every_library_error_is_a_bmfr_error(tmp_path, objects):
    garbage = tmp_path / "garbage.exr"
    garbage.write_bytes(b"not an exr")
    frame = bmfr.read_sequence(str(objects))[0]
    failing = [
        lambda: bmfr.read_sequence(str(tmp_path / "missing")),
        lambda: bmfr.read_exr(str(garbage)),
        lambda: bmfr.read_exr(str(tmp_path / "missing.exr")),
        lambda: bmfr.Filter().denoise(**{**frame, "view_projection": np.zeros((4, 4))}),
        lambda: bmfr.Filter("walr", walr_signal="diffuse-indirect").denoise(
            **{k: v for k, v in frame.items() if k != "diffuse_indirect"}),
        lambda: bmfr.Filter("bmfr", features="1,extra3").denoise_frame(frame),
        lambda: bmfr.Filter("bmfr", block_size=7),
        lambda: bmfr.write_exr(str(tmp_path / "no" / "such" / "folder" / "x.exr"),
                               np.zeros((2, 2, 3), np.float32)),
    ]
    if "cuda" in bmfr.backends():
        failing.append(lambda: bmfr.Device("cuda"))  # no GPU here: "no CUDA device"
    for call in failing:
        try:
            call()
        except bmfr.Error:
            continue
        pytest.fail("no bmfr.Error")


def test_without_numpy_the_import_says_so():
    code = "import sys; sys.modules['numpy'] = None; import bmfr"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode != 0 and "bmfr needs numpy" in r.stderr, r.stderr[-500:]


def test_numpy_numbers_notes_and_threads(objects, tmp_path):
    f = bmfr.Filter("bmfr", block_size=np.int64(16), noise=np.float64(0.01))
    seq = bmfr.read_sequence(str(objects))
    assert seq[np.int64(2)]["index"] == 2
    # A Cycles render with its own denoiser on: the note is a warning, once per sequence.
    for i in range(2):
        shutil.copy(os.path.join(ROOT, "tests", "data", "cycles_denoiser_on.exr"),
                    tmp_path / f"frame_{i:04d}.exr")
    vp = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, -1, -0.2], [0, 0, -1, 0]]
    frames = [{b: f"frame_{i:04d}.exr" for b in ("color", "albedo", "normal", "position")}
              | {"view_projection": vp} for i in range(2)]
    import json
    (tmp_path / "sequence.json").write_text(json.dumps(
        {"format": "bmfr-sequence", "version": 1, "width": 24, "height": 16, "frames": frames}))
    cycles = bmfr.read_sequence(str(tmp_path))
    with pytest.warns(UserWarning, match="Cycles' own denoiser was on") as caught:
        cycles[0]
        cycles[1]
    assert len(caught) == 1 and len(cycles.notes) == 1
    # Two Python threads on one filter take turns: the result is one of the orders' results.
    import threading
    frame = seq[0]
    errors = []

    def work():
        try:
            for _ in range(3):
                f.denoise_frame(frame)
        except Exception as e:  # noqa: BLE001 - reported below
            errors.append(e)

    threads = [threading.Thread(target=work) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors and f.stats["total_ms"] > 0


def test_flip_takes_ldr_images_and_says_what_is_wrong():
    grey = np.full((6, 5, 3), 0.5, np.float32)
    mean, flip_map = bmfr.flip(grey, grey)
    assert mean == 0.0 and flip_map.shape == (6, 5, 1) and flip_map.dtype == np.float32
    mean, flip_map = bmfr.flip(grey, np.ones_like(grey))
    assert 0.0 < mean <= 1.0 and np.allclose(flip_map[..., 0], mean)  # flat: one value
    with pytest.raises(ValueError, match=r"sRGB-encoded in \[0, 1\]"):
        bmfr.flip(grey, grey * 3)
    with pytest.raises(ValueError, match="reference is 5x6, test 5x5"):
        bmfr.flip(grey, grey[:5])
    with pytest.raises(ValueError, match=r"\(height, width, 3\)"):
        bmfr.flip(grey[..., 0], grey[..., 0])
