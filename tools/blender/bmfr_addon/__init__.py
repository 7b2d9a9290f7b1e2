"""bmfr for Blender: render a Cycles animation at a few samples per pixel and denoise it with
bmfr, temporally stable, from the Render properties.

Install the zip (Edit > Preferences > Add-ons > Install...; `python3 -m zipfile -c
bmfr_addon.zip tools/blender/bmfr_addon` makes it), enable "Render: bmfr denoiser", and use the
bmfr panel in Render properties. It needs the `bmfr` command (on PATH, or named in the add-on's
preferences). docs/blender.md.
"""
import os
import shutil
import subprocess

import bpy

from . import sequence

bl_info = {
    "name": "bmfr denoiser",
    "author": "bmfr",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Render > bmfr",
    "description": "Render the animation's passes with Cycles and denoise them with bmfr "
                   "(BMFR, SVGF, WALR, Mara 2017): temporally stable frames at a few samples",
    "category": "Render",
}


class BmfrPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__
    executable: bpy.props.StringProperty(
        name="bmfr command", subtype="FILE_PATH", default="",
        description="The bmfr program; empty: $BMFR_CLI, then bmfr on PATH")

    def draw(self, context):
        self.layout.prop(self, "executable")


class BmfrSceneSettings(bpy.types.PropertyGroup):
    filter: bpy.props.EnumProperty(
        name="Filter", default="bmfr",
        items=[("bmfr", "BMFR", "Blockwise multi-order feature regression (Koskela et al. 2019)"),
               ("svgf", "SVGF", "Spatiotemporal variance-guided filtering (Schied et al. 2017)"),
               ("walr", "WALR", "Weighted À-trous linear regression"),
               ("mara2017", "Mara 2017", "Mara et al. 2017, real-time glossy denoising")])
    preset: bpy.props.EnumProperty(
        name="Preset", default="quality",
        items=[("quality", "Quality", "the default: the paper's settings with bmfr's improvements "
                "beyond it"),
               ("faithful", "Faithful", "the paper's settings alone (the reproduction)")])
    samples: bpy.props.IntProperty(
        name="Samples", default=1, min=1, soft_max=64, max=65536,
        description="Samples per pixel of the frames to denoise")
    reference_samples: bpy.props.IntProperty(
        name="Reference samples", default=0, min=0, soft_max=4096,
        description="0: no reference. Else also render each frame at this many samples and "
                    "write bmfr's evaluation report (errors, temporal stability, viewer)")
    device: bpy.props.EnumProperty(
        name="Device", default="CPU",
        items=[("CPU", "CPU", "Cycles on the CPU"), ("GPU", "GPU", "the first GPU Cycles finds")])
    use_motion: bpy.props.BoolProperty(
        name="Motion vectors", default=True,
        description="Cycles' Vector pass and previous positions when anything moves, so that "
                    "moving objects keep their history (else reprojection by the camera)")
    use_visibility: bpy.props.BoolProperty(
        name="Sun visibility", default=True,
        description="Also render the brightest sun's shadow pass (1 sample, no bounces), which "
                    "BMFR fits so that hard shadows stay sharp; only when the scene has a sun")
    output: bpy.props.StringProperty(
        name="Output", subtype="DIR_PATH", default="//bmfr/",
        description="Folder for the passes (passes/), the denoised frames (denoised/) and the "
                    "report (report/)")


def bmfr_executable(context):
    prefs = context.preferences.addons[__package__].preferences
    exe = prefs.executable or os.environ.get("BMFR_CLI") or "bmfr"
    exe = bpy.path.abspath(exe) if exe.startswith("//") else exe
    found = shutil.which(exe)
    return found


def run_bmfr(exe, args):
    """Runs bmfr; returns (ok, the last lines of its output)."""
    r = subprocess.run([exe] + args, capture_output=True, text=True)
    text = (r.stdout + r.stderr).strip()
    return r.returncode == 0, "\n".join(text.splitlines()[-6:])


class BMFR_OT_render_denoise(bpy.types.Operator):
    """Render the animation's passes with Cycles and denoise them with bmfr"""
    bl_idname = "render.bmfr_denoise"
    bl_label = "Render and Denoise with bmfr"

    def execute(self, context):
        scene = context.scene
        s = scene.bmfr
        exe = bmfr_executable(context)
        if not exe:
            self.report({"ERROR"}, "bmfr: the bmfr command is not found: install it or name it "
                                   "in the add-on's preferences")
            return {"CANCELLED"}
        if s.output.startswith("//") and not bpy.data.filepath:
            self.report({"ERROR"}, "bmfr: the output folder is relative to the .blend file, "
                                   "which is not saved yet: save it or choose a folder")
            return {"CANCELLED"}
        out = os.path.abspath(bpy.path.abspath(s.output))
        passes, denoised, report = (os.path.join(out, n) for n in ("passes", "denoised", "report"))
        if os.path.isdir(report) and not os.path.exists(os.path.join(report, "table.json")):
            self.report({"ERROR"}, f"bmfr: {report} is not an earlier bmfr report; not replacing it")
            return {"CANCELLED"}
        opts = sequence.Options(spp=s.samples, reference_spp=s.reference_samples,
                                device=s.device, motion="auto" if s.use_motion else "off",
                                visibility="auto" if s.use_visibility else "off")
        wm = context.window_manager
        total = scene.frame_end - scene.frame_start + 1
        wm.progress_begin(0, total + 2)
        try:
            return self.run(scene, s, exe, passes, denoised, report, opts, total)
        finally:
            wm.progress_end()

    def run(self, scene, s, exe, passes, denoised, report, opts, total):
        wm = bpy.context.window_manager

        def progress(done, total, text):
            wm.progress_update(done)
            print(f"bmfr: rendered {text}", flush=True)

        try:
            summary = sequence.render_sequence(scene, passes, opts, progress)
        except sequence.SequenceError as e:
            self.report({"ERROR"}, f"bmfr: cannot render this scene for bmfr: {e}")
            return {"CANCELLED"}
        ok, text = run_bmfr(exe, ["denoise", passes, "-o", denoised, "--filter", s.filter,
                                  "--preset", s.preset, "--overwrite", "-q"])
        wm.progress_update(total + 1)
        if not ok:
            self.report({"ERROR"}, f"bmfr denoise failed: {text}")
            return {"CANCELLED"}
        last = summary["first"] + summary["frames"] - 1
        message = (f"bmfr: {summary['frames']} frames denoised with {s.filter} ({s.preset}) "
                   f"into {denoised} (denoised_0000 is Blender frame {summary['first']}, "
                   f"the last frame {last})")
        if s.reference_samples > 0:
            if os.path.isdir(report):
                shutil.rmtree(report)
            ok, text = run_bmfr(exe, ["eval", "-r", passes, "-m", "noisy", "-m",
                                      f"{s.filter}={denoised}", "-o", report, "-q"])
            if not ok:
                self.report({"ERROR"}, f"bmfr eval failed: {text}")
                return {"CANCELLED"}
            message += f"; report: {os.path.join(report, 'report.html')}"
        if summary["without_previous_position"]:
            self.report({"WARNING"}, "bmfr: no previous position for "
                        + ", ".join(summary["without_previous_position"])
                        + " (no node material)")
        self.report({"INFO"}, message)
        return {"FINISHED"}


class BMFR_PT_render(bpy.types.Panel):
    bl_label = "bmfr"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"

    def draw(self, context):
        layout = self.layout
        s = context.scene.bmfr
        layout.use_property_split = True
        for name in ("filter", "preset", "samples", "device", "use_motion", "use_visibility",
                     "reference_samples", "output"):
            layout.prop(s, name)
        if context.scene.render.engine != "CYCLES":
            layout.label(text="Renders with Cycles", icon="INFO")
        layout.operator(BMFR_OT_render_denoise.bl_idname, icon="RENDER_ANIMATION")


classes = (BmfrPreferences, BmfrSceneSettings, BMFR_OT_render_denoise, BMFR_PT_render)


def register():
    for c in classes:
        bpy.utils.register_class(c)
    bpy.types.Scene.bmfr = bpy.props.PointerProperty(type=BmfrSceneSettings)


def unregister():
    del bpy.types.Scene.bmfr
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
