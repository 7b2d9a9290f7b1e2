"""Run inside Blender by addon_test.py: the scene checks of bmfr_addon/sequence.py refuse motion
blur, depth of field, a transparent film and a camera that is not perspective, each with its
reason; motion is detected from the objects (the test scene's sphere) and not where nothing
moves.

    checks_driver.py -- ADDON_PARENT_DIR SCENE.blend
"""
import sys

import bpy

parent, blend = sys.argv[sys.argv.index("--") + 1:][:2]
sys.path.insert(0, parent)
from bmfr_addon import sequence  # noqa: E402

bpy.ops.wm.open_mainfile(filepath=blend)
scene = bpy.context.scene
opts = sequence.Options()
sequence.check_scene(scene, opts)  # the test scene passes


def refused(change, undo, reason):
    change()
    try:
        sequence.check_scene(scene, opts)
    except sequence.SequenceError as e:
        assert reason in str(e), f"{reason!r} not in {e}"
        print("refused:", e)
    else:
        raise AssertionError(f"not refused: {reason}")
    finally:
        undo()


r, cam = scene.render, scene.camera.data
refused(lambda: setattr(r, "use_motion_blur", True), lambda: setattr(r, "use_motion_blur", False),
        "motion blur is on")
refused(lambda: setattr(cam.dof, "use_dof", True), lambda: setattr(cam.dof, "use_dof", False),
        "depth of field is on")
refused(lambda: setattr(r, "film_transparent", True),
        lambda: setattr(r, "film_transparent", False), "the film is transparent")
refused(lambda: setattr(cam, "type", "ORTHO"), lambda: setattr(cam, "type", "PERSP"),
        "bmfr needs a perspective camera")
assert sequence.moving_objects(scene, 1, scene.frame_end + 1) == ["sphere"]
scene.objects["sphere"].animation_data_clear()
assert sequence.moving_objects(scene, 1, scene.frame_end + 1) == []
print("scene checks passed")
