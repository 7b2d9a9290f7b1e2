"""The key light's visibility pass: the sun's noise-free shadow at the first hit times its cosine.

bmfr's `visibility` buffer (docs/library.md#visibility) lets BMFR fit a hard shadow across a
block instead of averaging it. Cycles has no shadow pass, so it is rendered: every material
becomes white diffuse (keeping its alpha, so leaves and chains cast and let through what they
do in the frame), the sun is the only light, with no angle, white, at a strength of pi so that
a white diffuse surface facing it reads 1, and paths stop at the first hit. One sample through
the frame's jittered point is then exact. Only a sun is taken: a point or spot light's
falloff is not a visibility. An object without any material reads Cycles' default grey (0.8)
where the sun reaches it. The animation and drivers of what the pass sets are muted while it
renders (a render evaluates them over a value set by hand). Alpha is found by following the
active output's surface back through mix and add shaders to a Principled BSDF; transparency
built otherwise (a Transparent BSDF in a mix, a Principled inside a node group) is not seen,
and such a surface casts a solid shadow.
"""
import math

import bpy

NODE_PREFIX = "bmfr_visibility_"
PASS_THROUGH = {"MIX_SHADER", "ADD_SHADER", "REROUTE"}


def key_sun(scene, layer):
    """The brightest sun that renders in `layer`, or None."""
    def renders(o):
        return (not o.hide_render and o.name in layer.objects
                and not any(c.hide_render for c in o.users_collection))

    suns = [o for o in scene.objects
            if o.type == "LIGHT" and o.data.type == "SUN" and o.data.energy > 0 and renders(o)]
    return max(suns, key=lambda o: o.data.energy * max(o.data.color), default=None)


def _alpha_source(socket):
    """The socket or value that feeds the alpha of the Principled BSDF behind `socket` (through
    mix and add shaders), or 1."""
    seen = set()
    todo = [link.from_node for link in socket.links]
    while todo:
        node = todo.pop(0)
        if node.name in seen:
            continue
        seen.add(node.name)
        if node.type == "BSDF_PRINCIPLED":
            alpha = node.inputs["Alpha"]
            return alpha.links[0].from_socket if alpha.is_linked else alpha.default_value
        if node.type in PASS_THROUGH:
            todo += [link.from_node for i in node.inputs for link in i.links
                     if i.type == "SHADER" or node.type == "REROUTE"]
    return 1.0


def _relink(tree, socket, source, undo):
    """Links `source` (or nothing) into `socket`, with the undo step that puts back what was
    there."""
    before = socket.links[0].from_socket if socket.is_linked else None
    for link in socket.links:
        tree.links.remove(link)
    if source is not None:
        tree.links.new(source, socket)

    def put_back():
        for link in socket.links:
            tree.links.remove(link)
        if before is not None:
            tree.links.new(before, socket)

    undo.append(put_back)


def _whiten(material, undo):
    tree = material.node_tree
    output = tree.get_output_node("CYCLES")
    if output is None:
        return
    surface = output.inputs["Surface"]
    alpha = _alpha_source(surface)
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (1, 1, 1, 1)
    clear = tree.nodes.new("ShaderNodeBsdfTransparent")
    mix = tree.nodes.new("ShaderNodeMixShader")
    added = [diffuse, clear, mix]
    for n in added:
        n.name = NODE_PREFIX + n.name
    undo.append(lambda: [tree.nodes.remove(n) for n in added])
    if isinstance(alpha, float):
        mix.inputs["Fac"].default_value = alpha
    else:
        tree.links.new(alpha, mix.inputs["Fac"])
    tree.links.new(clear.outputs[0], mix.inputs[1])
    tree.links.new(diffuse.outputs[0], mix.inputs[2])
    _relink(tree, surface, mix.outputs[0], undo)
    _relink(tree, output.inputs["Volume"], None, undo)


def _set(owner, name, value, undo):
    old = getattr(owner, name)
    if not isinstance(old, (bpy.types.ID, str)) and hasattr(old, "__len__"):
        old = tuple(old)  # a colour or array reads the live value
    setattr(owner, name, value)
    undo.append(lambda: setattr(owner, name, old))


def _overrides(scene, sun):
    """(ID, data path, value): what the pass sets besides the materials."""
    o = [(scene, "world", None), (sun.data, "angle", 0.0), (sun.data, "color", (1.0, 1.0, 1.0)),
         (sun.data, "energy", math.pi), (sun.data, "use_nodes", False),
         (scene, "cycles.samples", 1), (scene, "cycles.max_bounces", 0),
         (scene, "cycles.use_denoising", False), (scene, "cycles.sample_clamp_direct", 0.0),
         (scene, "cycles.film_exposure", 1.0), (scene, "render.use_persistent_data", False)]
    o += [(light, "hide_render", True) for light in scene.objects
          if light.type == "LIGHT" and light != sun and not light.hide_render]
    return o


def _mute(id_, path, undo):
    """Mutes the animation and drivers of id_'s `path`: a render evaluates them over any value
    set by hand."""
    anim = id_.animation_data
    if anim is None:
        return
    curves = list(anim.drivers) + (list(anim.action.fcurves) if anim.action else [])
    for fc in curves:
        if fc.data_path == path and not fc.mute:
            fc.mute = True
            undo.append(lambda fc=fc: setattr(fc, "mute", False))


def prepare(scene, sun, undo):
    """Turns the scene into the visibility render of `sun`, appending to `undo` the steps that
    put it back (to run last first)."""
    for m in bpy.data.materials:
        if m.use_nodes and m.node_tree is not None:
            _whiten(m, undo)
        elif not m.use_nodes:
            _set(m, "diffuse_color", (1.0, 1.0, 1.0, 1.0), undo)
    for id_, path, value in _overrides(scene, sun):
        _mute(id_, path, undo)
        owner, _, name = path.rpartition(".")
        _set(id_.path_resolve(owner) if owner else id_, name, value, undo)
