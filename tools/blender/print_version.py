"""Prints this Blender's version and whether its Cycles has OIDN (blender_run.py reads it)."""
import bpy
import _cycles  # noqa: E402 (importable once bpy is, in PyPI's module)

print("blender version", bpy.app.version_string, "oidn", _cycles.with_openimagedenoise)
