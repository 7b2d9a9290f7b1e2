"""The key light's visibility pass: the sun's noise-free shadow at the first hit times its cosine.

bmfr's `visibility` buffer (docs/library.md#visibility) lets BMFR fit a hard shadow across a
block instead of averaging it. Cycles has no shadow pass, so it is rendered: every material
becomes white diffuse (keeping its alpha, so leaves and chains cast and let through what they
do in the frame), the sun is the only light, with no angle, white, at a strength of pi so that
a white diffuse surface facing it reads 1, and paths stop at the first hit. One sample through
the frame's jittered point is then exact. Only a sun is taken: a point or spot light's
falloff is not a visibility. A surface without a node material reads Cycles' default grey
(0.8) where the sun reaches it.
"""
import math

import bpy

NODE_PREFIX = "bmfr_visibility_"


def key_sun(scene):
    """The brightest sun that renders, or None."""
    suns = [o for o in scene.objects
            if o.type == "LIGHT" and o.data.type == "SUN" and not o.hide_render
            and o.data.energy > 0]
    return max(suns, key=lambda o: o.data.energy * max(o.data.color), default=None)


def _alpha_source(tree):
    """The socket or value that feeds the material's alpha (Principled BSDF), or 1."""
    for node in tree.nodes:
        if node.type == "BSDF_PRINCIPLED":
            alpha = node.inputs["Alpha"]
            return alpha.links[0].from_socket if alpha.is_linked else alpha.default_value
    return 1.0


def _whiten(material, undo):
    tree = material.node_tree
    outputs = [n for n in tree.nodes if n.type == "OUTPUT_MATERIAL"]
    if not outputs:
        return
    out = outputs[0].inputs["Surface"]
    before = out.links[0].from_socket if out.is_linked else None
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (1, 1, 1, 1)
    clear = tree.nodes.new("ShaderNodeBsdfTransparent")
    mix = tree.nodes.new("ShaderNodeMixShader")
    added = [diffuse, clear, mix]
    for n in added:
        n.name = NODE_PREFIX + n.name
    alpha = _alpha_source(tree)
    if isinstance(alpha, float):
        mix.inputs["Fac"].default_value = alpha
    else:
        tree.links.new(alpha, mix.inputs["Fac"])
    tree.links.new(clear.outputs[0], mix.inputs[1])
    tree.links.new(diffuse.outputs[0], mix.inputs[2])
    tree.links.new(mix.outputs[0], out)

    def put_back():
        for n in added:
            tree.nodes.remove(n)
        if before is not None:
            tree.links.new(before, out)

    undo.append(put_back)


def _set(owner, name, value, undo):
    old = getattr(owner, name)
    setattr(owner, name, value)
    undo.append(lambda: setattr(owner, name, old))


def prepare(scene, sun):
    """Turns the scene into the visibility render of `sun`; returns the undo steps, last first
    to run (the caller runs them in reverse)."""
    undo = []
    materials = {s.material for o in scene.objects if o.type in {"MESH", "CURVE", "SURFACE",
                                                                 "META", "FONT"}
                 for s in o.material_slots if s.material is not None}
    for m in materials:
        if m.use_nodes:
            _whiten(m, undo)
    for o in scene.objects:
        if o.type == "LIGHT" and o != sun and not o.hide_render:
            _set(o, "hide_render", True, undo)
    _set(scene, "world", None, undo)
    _set(sun.data, "angle", 0.0, undo)
    _set(sun.data, "color", (1.0, 1.0, 1.0), undo)
    _set(sun.data, "energy", math.pi, undo)
    c = scene.cycles
    _set(c, "samples", 1, undo)
    _set(c, "max_bounces", 0, undo)
    _set(c, "use_denoising", False, undo)
    _set(scene.render, "use_persistent_data", False, undo)
    return undo

