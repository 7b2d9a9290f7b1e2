"""Run inside Blender by addon_test.py: installs the add-on's zip, enables it, opens the scene,
sets the bmfr panel's settings and runs its operator, headless. Prints what the operator
returned and reported.

    addon_driver.py -- ZIP SCENE.blend OUTPUT BMFR_CLI [--motion-blur]
"""
import sys

import bpy

zip_path, blend, output, cli = sys.argv[sys.argv.index("--") + 1:][:4]
bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
bpy.ops.preferences.addon_enable(module="bmfr_addon")
bpy.ops.wm.open_mainfile(filepath=blend)
bpy.context.preferences.addons["bmfr_addon"].preferences.executable = cli
scene = bpy.context.scene
s = scene.bmfr
s.filter, s.preset, s.samples, s.reference_samples, s.output = "svgf", "quality", 1, 16, output
if "--motion-blur" in sys.argv:
    scene.render.use_motion_blur = True
# The panel draws (as Blender would in the Render properties) without errors.
assert "BMFR_PT_render" in dir(bpy.types), "the panel is not registered"


def user_state():
    """What the user set up, which the operator must leave as it was."""
    layer = bpy.context.view_layer
    return (scene.render.engine, scene.cycles.filter_width, scene.cycles.samples,
            scene.render.image_settings.file_format, scene.frame_current, layer.use_pass_vector,
            layer.use_pass_position, len(layer.aovs),
            sorted((m.name, len(m.node_tree.nodes)) for m in bpy.data.materials if m.use_nodes),
            sorted((o.name, tuple(o.keys())) for o in scene.objects),
            (scene.camera.data.shift_x, scene.camera.data.shift_y))


scene.frame_set(2)
before = user_state()
try:
    result = bpy.ops.render.bmfr_denoise()
except RuntimeError as e:  # an operator's ERROR report raises in background mode
    result = {"CANCELLED"}
    print("operator error:", e)
print("operator result:", sorted(result))
print("scene as it was:", user_state() == before, "" if user_state() == before else
      f"{before} -> {user_state()}")
