"""Renders the sun scene's sequence through bmfr_addon.sequence inside Blender and checks that
the scene is as it was afterwards: the materials' nodes and links, the lights, the world and
the render settings the visibility pass changes; and that an animated light is not counted as
motion.

    blender -b --factory-startup --python tests/blender/visibility_driver.py -- SCENE.blend OUT
"""
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../tools/blender"))
from bmfr_addon import sequence  # noqa: E402


def snapshot(scene):
    s = {"world": scene.world.name if scene.world else None,
         "samples": scene.cycles.samples, "bounces": scene.cycles.max_bounces,
         "persistent": scene.render.use_persistent_data, "frame": scene.frame_current}
    for o in scene.objects:
        if o.type == "LIGHT":
            s[o.name] = (o.hide_render, tuple(o.data.color), getattr(o.data, "angle", None),
                         o.data.energy, o.data.use_nodes)
    for m in bpy.data.materials:
        if m.node_tree:
            s[m.name] = (sorted(n.name for n in m.node_tree.nodes),
                         sorted((link.from_node.name, link.from_socket.identifier,
                                 link.to_node.name, link.to_socket.identifier)
                                for link in m.node_tree.links))
    return s


argv = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.open_mainfile(filepath=argv[0])
scene = bpy.context.scene
scene.frame_set(2)
before = snapshot(scene)
summary = sequence.render_sequence(scene, argv[1], sequence.Options(frames=(1, 3)))
# Only the sun's strength is animated: no surface moves, so no Vector pass.
if summary["moving"] or summary["motion"]:
    sys.exit(f"counted as moving: {summary['moving']}")
after = snapshot(scene)
changed = {k: (before.get(k), after.get(k)) for k in set(before) | set(after)
           if before.get(k) != after.get(k)}
if changed:
    sys.exit(f"the scene changed: {changed}")
print("scene restored")
