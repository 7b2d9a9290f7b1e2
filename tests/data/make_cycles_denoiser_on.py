"""Renders cycles_denoiser_on.exr: Blender's default scene, 24x16, 1 sample, Cycles' own denoiser
(OpenImageDenoise) on with the denoising data passes, as one multilayer EXR; the file then holds
both Combined (Cycles' denoised result) and Noisy Image. Debian's Blender 3.4 is built without
OpenImageDenoise, so this was run with PyPI's bpy 4.2.0 (Blender as a Python module):
    python3 -m venv venv && venv/bin/pip install bpy==4.2.0
    venv/bin/python make_cycles_denoiser_on.py -- cycles_denoiser_on.exr
"""
import bpy, sys
out = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=False)
s = bpy.context.scene
s.render.engine = "CYCLES"
s.cycles.device = "CPU"
s.cycles.samples = 1
s.cycles.use_denoising = True
s.cycles.denoiser = "OPENIMAGEDENOISE"
s.render.resolution_x, s.render.resolution_y, s.render.resolution_percentage = 24, 16, 100
s.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
s.render.image_settings.exr_codec = "ZIP"
l = s.view_layers[0]
l.use_pass_combined = True
l.use_pass_normal = True
l.use_pass_position = True
l.cycles.denoising_store_passes = True
s.render.filepath = out
bpy.ops.render.render(write_still=True)
