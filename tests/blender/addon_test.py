"""The Blender add-on, headless: the zip of tools/blender/bmfr_addon is installed and enabled,
and its operator renders the test scene's passes, denoises them with bmfr and writes the
evaluation report, leaving the user's scene (render settings, passes, materials, objects, current
frame) as it was; with motion blur on it refuses, saying why. The scene checks refuse depth of
field, a transparent film and a camera that is not perspective too (checks_driver.py). Exit 77 (skipped) without
Blender."""
import json
import os
import shutil
import sys
import tempfile
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "../../tools/blender"))
import blender_run  # noqa: E402

CLI = os.environ["BMFR_CLI"]


def main():
    blender_run.require_blender()
    work = tempfile.mkdtemp(prefix="bmfr_addon_")
    zip_path = os.path.join(work, "bmfr_addon.zip")
    addon = os.path.join(blender_run.ROOT, "tools/blender/bmfr_addon")
    with zipfile.ZipFile(zip_path, "w") as z:  # as `python3 -m zipfile -c` makes it
        for name in sorted(os.listdir(addon)):
            if name.endswith(".py"):
                z.write(os.path.join(addon, name), f"bmfr_addon/{name}")
    blend = os.path.join(work, "room.blend")
    blender_run.make_scene(blend, 3, "48x27")
    # Installed into a scratch user folder, not the user's own.
    env = {"BLENDER_USER_SCRIPTS": os.path.join(work, "scripts"),
           "BLENDER_USER_CONFIG": os.path.join(work, "config")}
    driver = os.path.join(HERE, "addon_driver.py")
    out = os.path.join(work, "out")
    log = blender_run.run_script(driver, zip_path, blend, out, CLI, env=env)
    assert "operator result: ['FINISHED']" in log, log[-3000:]
    assert "frames denoised with svgf (quality)" in log, log[-3000:]
    assert "scene as it was: True" in log, log[-3000:]
    denoised = sorted(f for f in os.listdir(os.path.join(out, "denoised")) if f.endswith(".exr"))
    assert denoised == [f"denoised_{k:04d}.exr" for k in range(3)], denoised
    assert os.path.exists(os.path.join(out, "report", "report.html"))
    table = json.load(open(os.path.join(out, "report", "table.json")))
    rmse = {n: m["mean"]["rmse"] for n, m in table["methods"].items()}
    print("add-on run, 48x27, 3 frames, reference 16 spp: tone-mapped RMSE", rmse)
    assert rmse["svgf"] < rmse["noisy"], rmse
    doc = json.load(open(os.path.join(out, "passes", "sequence.json")))
    assert doc.get("motion_convention") == "cycles", "the moving sphere got no motion vectors"
    # Again into the same folder: the operator replaces its own outputs.
    log = blender_run.run_script(driver, zip_path, blend, out, CLI, env=env)
    assert "operator result: ['FINISHED']" in log, log[-3000:]
    # Motion blur on: refused with the reason, nothing denoised.
    out2 = os.path.join(work, "blurred")
    log = blender_run.run_script(driver, zip_path, blend, out2, CLI, "--motion-blur", env=env)
    assert "operator result: ['CANCELLED']" in log and "motion blur is on" in log, log[-3000:]
    assert "scene as it was: True" in log, log[-3000:]
    assert not os.path.exists(os.path.join(out2, "denoised"))
    # The scene checks, one by one, and motion detection.
    log = blender_run.run_script(os.path.join(HERE, "checks_driver.py"),
                                 os.path.dirname(addon), blend)
    assert "scene checks passed" in log, log[-3000:]
    shutil.rmtree(work)  # kept for a look when an assertion failed
    print("blender add-on test passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
