"""The test scene's moving sphere (make_test_scene.py and its OUT.blend.json), read back from a
rendered sequence: which pixels are on it, and where it was. No bpy needed."""
import numpy as np


def blender_frame(entry):
    """The Blender frame a sequence.json entry was rendered at (frame_NNNN.exr)."""
    name = entry["color"] if isinstance(entry["color"], str) else entry["color"]["file"]
    return int(name.split("_")[-1].split(".")[0])


def velocity(path):
    return np.array(path["velocity_per_frame"])


def on_sphere(position, path, frame):
    """Pixels whose position lies on the sphere at Blender frame `frame`. A UV sphere is
    faceted: its points lie between the faces' planes and the radius."""
    centre = np.array(path["start"]) + velocity(path) * (frame - path["first_frame"])
    d = np.linalg.norm(position - centre, axis=-1)
    return (d > 0.98 * path["radius"]) & (d < path["radius"] + 1e-5)
