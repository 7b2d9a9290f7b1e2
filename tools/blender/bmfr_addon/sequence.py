"""Renders a Blender scene's animation with Cycles into a bmfr sequence folder.

Per frame one multilayer EXR at `spp` samples per pixel with the passes bmfr reads (Combined,
Denoising Albedo, Normal, Position, Emit; Cycles' names) and, when anything in the scene moves,
Cycles' Vector pass (motion) and each pixel's previous world position (an AOV), optionally a
reference of more samples, and OUT/sequence.json with the camera's view-projection in bmfr's
convention and the frame's sub-pixel jitter. Files are named by Blender frame number.

Conventions (those of bmfr's FrameInput, include/bmfr/frame.h):
- view_projection is row-major and acts on column vectors; NDC y grows downwards, so Blender's
  OpenGL projection gets its second row negated.
- The primary ray of pixel (x, y) goes through the screen point (x + 0.5 + jx, y + 0.5 + jy),
  pixels, y down. Cycles' pixel filter is shrunk to 0.01 px so that every ray of a frame goes
  through that one point, and the jitter (Halton 2, 3, as bmfr render) is made with the camera's
  lens shift. The jitter written is the one realised, read back from the two projections.
- Motion is Cycles' Vector pass as it is ("motion_convention": "cycles": bmfr flips its y and
  adds the jitter of both frames, which Cycles leaves out). The previous position is the
  pixel's world position moved by its object's motion from this frame to the previous one,
  written as an offset from the position, which bmfr adds back (exact for rigid motion;
  deforming meshes and instances get their object's transform only; a pixel no material writes
  reads as static).
- References are rendered at the pixel centres, as bmfr render's are.
"""
import json
import os

import bpy

from . import visibility as key_light

PASS_NOTE = "Combined, Denoising Albedo, Normal, Position, Emit (Cycles pass names)"
PREVIOUS_AOV = "bmfr_previous_position"
ROW_PROPERTY = "bmfr_previous_row"  # + 0, 1, 2: this frame's world -> the previous frame's


# Object types that render surfaces (and so get the previous-position AOV).
GEOMETRY = {"MESH", "CURVE", "SURFACE", "META", "FONT"}
# Object types that render something a pixel's motion vector follows.
SURFACES = GEOMETRY | {"CURVES", "POINTCLOUD", "VOLUME"}
# Modifiers that may move the surface from frame to frame (counted as moving, not checked).
DEFORMING = {"ARMATURE", "CLOTH", "SOFT_BODY", "WAVE", "NODES", "MESH_CACHE",
             "MESH_SEQUENCE_CACHE", "HOOK", "OCEAN", "DYNAMIC_PAINT", "EXPLODE", "FLUID",
             "PARTICLE_SYSTEM", "SHRINKWRAP", "SURFACE_DEFORM", "MESH_DEFORM", "LATTICE",
             "CURVE", "SIMPLE_DEFORM", "DISPLACE", "WARP", "CAST", "SMOOTH", "LAPLACIANDEFORM"}


class SequenceError(Exception):
    """A scene or setting render_sequence cannot render faithfully; the message says why."""


class Options:
    def __init__(self, spp=1, reference_spp=0, frames=None, width=None, height=None, jitter=True,
                 seed=1, device="CPU", motion="auto", denoiser=False, visibility="auto"):
        self.spp = spp                      # samples per pixel of the noisy frames, >= 1
        self.reference_spp = reference_spp  # 0: no reference
        self.frames = frames                # (first, last): Blender frames first..last-1
        self.width, self.height = width, height
        self.jitter = jitter
        self.seed = seed
        self.device = device                # CPU or GPU (the GPU Cycles finds)
        self.motion = motion                # auto (when anything moves), on or off
        self.denoiser = denoiser            # Cycles' own OIDN per frame, beside the noisy image
        self.visibility = visibility        # auto (the brightest sun's, when there is one) or off


def halton(index, base):
    f, r = 1.0, 0.0
    while index > 0:
        f /= base
        r += f * (index % base)
        index //= base
    return r


def projection(camera, depsgraph, render):
    return camera.calc_matrix_camera(depsgraph, x=render.resolution_x, y=render.resolution_y,
                                     scale_x=render.pixel_aspect_x, scale_y=render.pixel_aspect_y)


def view_projection(camera, depsgraph, render):
    """World to clip in bmfr's convention (NDC y down)."""
    m = projection(camera, depsgraph, render) @ camera.matrix_world.inverted()
    rows = [list(m[r]) for r in range(4)]
    rows[1] = [-v for v in rows[1]]
    return rows


def write_json_atomically(path, doc):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)


def check_scene(scene, opts):
    """What would make the passes wrong, as one SequenceError listing every problem."""
    problems = []
    if scene.camera is None:
        problems.append("the scene has no active camera")
    elif scene.camera.type != "CAMERA":
        problems.append(f"the active camera '{scene.camera.name}' is not a camera")
    else:
        cam = scene.camera.data
        if cam.type != "PERSP":
            problems.append(f"the camera is {cam.type.lower()}: bmfr needs a perspective camera")
        if cam.dof.use_dof:
            problems.append("depth of field is on (Camera > Depth of Field): the features are "
                            "sharp where the image is blurred; turn it off")
    if scene.render.use_motion_blur:
        problems.append("motion blur is on (Render > Motion Blur): Cycles then writes no Vector "
                        "pass and the image is blurred where the features are not; turn it off")
    if scene.render.film_transparent:
        problems.append("the film is transparent (Render > Film > Transparent): the background "
                        "has no colour to denoise; turn it off")
    if opts.spp < 1:
        problems.append(f"{opts.spp} samples per pixel: at least 1")
    if opts.reference_spp < 0:
        problems.append(f"{opts.reference_spp} reference samples per pixel: 0 (none) or more")
    if opts.device not in ("CPU", "GPU"):
        problems.append(f"device {opts.device}: CPU or GPU")
    if opts.motion not in ("auto", "on", "off"):
        problems.append(f"motion {opts.motion}: auto, on or off")
    if opts.visibility not in ("auto", "off"):
        problems.append(f"visibility {opts.visibility}: auto or off")
    if problems:
        raise SequenceError("; ".join(problems))


def frame_range(scene, opts):
    first, last = scene.frame_start, scene.frame_end + 1
    if opts.frames:
        first, last = opts.frames
    if last <= first:
        raise SequenceError(f"empty frame range {first}:{last}")
    return first, last


def use_gpu(scene, state):
    """Cycles on the first GPU backend that finds a device, or a SequenceError. The user's
    device preferences are put back afterwards (state)."""
    prefs = bpy.context.preferences.addons["cycles"].preferences
    backend_before = prefs.compute_device_type
    use_before = [(d, d.use) for d in prefs.devices]

    def put_back():
        prefs.compute_device_type = backend_before
        for d, use in use_before:
            d.use = use

    state.undo.append(put_back)
    for backend in ("OPTIX", "CUDA", "HIP", "ONEAPI", "METAL"):
        try:
            prefs.compute_device_type = backend
        except TypeError:  # not in this build of Blender
            continue
        prefs.get_devices()
        devices = [d for d in prefs.devices if d.type == backend]
        if devices:
            for d in prefs.devices:
                d.use = d.type == backend
            scene.cycles.device = "GPU"
            return f"{backend}: " + ", ".join(d.name for d in devices)
    raise SequenceError("--device GPU: Cycles finds no GPU (tried OptiX, CUDA, HIP, oneAPI, "
                        "Metal); use --device CPU")


def moving_objects(scene, first, last):
    """Names of the objects that render surfaces (and the empties that instance a collection)
    whose world matrix changes over the frames, and of those that deform (armature, shape keys,
    animated modifiers: counted as moving). Cameras, lights and other empties move no surface:
    a camera-only animation needs no Vector pass."""
    objs = [o for o in scene.objects if o.type in SURFACES
            or (o.type == "EMPTY" and o.instance_type == "COLLECTION")]
    start = {}
    moving = set()
    for frame in range(first, last):
        scene.frame_set(frame)
        for o in objs:
            m = [list(r) for r in o.matrix_world]
            if o.name not in start:
                start[o.name] = m
            elif any(abs(a - b) > 1e-7 for ra, rb in zip(m, start[o.name]) for a, b in zip(ra, rb)):
                moving.add(o.name)
    for o in objs:
        keys = getattr(o.data, "shape_keys", None)
        if any(m.type in DEFORMING for m in o.modifiers) or (keys and keys.animation_data) or (
                getattr(o.data, "animation_data", None)):
            moving.add(o.name)
    return sorted(moving)


def add_previous_position_aov(scene, layer, state):
    """Every node material writes PREVIOUS_AOV: its object's row properties (this frame's world
    to the previous frame's) applied to the shading position, less that position (an offset, so
    that a pixel no material writes, 0, reads as static). Returns the objects whose materials
    cannot (no node material). `state` (SceneState) takes the AOV and the nodes back out."""
    if PREVIOUS_AOV not in [a.name for a in layer.aovs]:
        aov = layer.aovs.add()
        aov.name = PREVIOUS_AOV
        aov.type = "COLOR"
        state.undo.append(lambda: remove_aov(layer))
    done = set()
    without = []
    for o in scene.objects:
        if o.type not in GEOMETRY:
            continue
        mats = [s.material for s in o.material_slots if s.material]
        if not mats or any(not m.use_nodes for m in mats):
            without.append(o.name)
        for m in mats:
            if m.use_nodes and m.name not in done:
                done.add(m.name)
                added = wire_aov(m.node_tree)
                state.undo.append(lambda t=m.node_tree, names=added: remove_nodes(t, names))
    return without


def remove_aov(layer):
    """The AOV collection has no remove(): the view layer's operator removes the active one."""
    layer.active_aov_index = [a.name for a in layer.aovs].index(PREVIOUS_AOV)
    bpy.ops.scene.view_layer_remove_aov()


def remove_nodes(tree, names):
    for node in [n for n in tree.nodes if n.name in names]:
        tree.nodes.remove(node)


def wire_aov(tree):
    """Adds the AOV's nodes to a material; returns their names."""
    if any(n.bl_idname == "ShaderNodeOutputAOV" and n.name == PREVIOUS_AOV for n in tree.nodes):
        return []
    before = {n.name for n in tree.nodes}
    nodes, links = tree.nodes, tree.links
    geometry = nodes.new("ShaderNodeNewGeometry")
    combine = nodes.new("ShaderNodeCombineXYZ")
    for r, axis in enumerate("XYZ"):
        attr = nodes.new("ShaderNodeAttribute")
        attr.attribute_type = "OBJECT"
        attr.attribute_name = f"{ROW_PROPERTY}{r}"
        dot = nodes.new("ShaderNodeVectorMath")
        dot.operation = "DOT_PRODUCT"
        links.new(attr.outputs["Vector"], dot.inputs[0])
        links.new(geometry.outputs["Position"], dot.inputs[1])
        add = nodes.new("ShaderNodeMath")
        add.operation = "ADD"
        links.new(dot.outputs["Value"], add.inputs[0])
        links.new(attr.outputs["Alpha"], add.inputs[1])
        links.new(add.outputs["Value"], combine.inputs[axis])
    offset = nodes.new("ShaderNodeVectorMath")
    offset.operation = "SUBTRACT"
    links.new(combine.outputs["Vector"], offset.inputs[0])
    links.new(geometry.outputs["Position"], offset.inputs[1])
    out = nodes.new("ShaderNodeOutputAOV")
    out.name = PREVIOUS_AOV
    if hasattr(out, "aov_name"):
        out.aov_name = PREVIOUS_AOV
    else:
        out.name = PREVIOUS_AOV
    links.new(offset.outputs["Vector"], out.inputs["Color"])
    return [n.name for n in tree.nodes if n.name not in before]


def set_previous_rows(scene, frame, objects):
    """Each object's ROW_PROPERTY0..2 at `frame`: the rows of M(frame - 1) M(frame)^-1."""
    scene.frame_set(frame - 1)
    before = {o.name: o.matrix_world.copy() for o in objects}
    scene.frame_set(frame)
    for o in objects:
        delta = before[o.name] @ o.matrix_world.inverted_safe()
        for r in range(3):
            o[f"{ROW_PROPERTY}{r}"] = [delta[r][0], delta[r][1], delta[r][2], delta[r][3]]


class SceneState:
    """What rendering changes in the user's scene (render settings, passes, the AOV and its
    nodes, objects' properties, the current frame), put back by restore()."""

    def __init__(self, scene, layer):
        self.saved = []
        self.undo = []
        r, c = scene.render, scene.cycles
        for owner, names in (
                (scene, ["frame_current"]),
                (r, ["engine", "resolution_x", "resolution_y", "resolution_percentage",
                     "use_persistent_data", "use_file_extension", "filepath"]),
                (r.image_settings, ["file_format", "color_depth", "exr_codec"]),
                (c, ["device", "samples", "seed", "use_adaptive_sampling", "use_denoising",
                     "denoiser", "filter_width"]),
                (layer, ["use_pass_combined", "use_pass_normal", "use_pass_position",
                         "use_pass_emit", "use_pass_vector"]),
                (layer.cycles, ["denoising_store_passes", "use_denoising"])):
            for name in names:
                if hasattr(owner, name):
                    self.saved.append((owner, name, getattr(owner, name)))

    def restore(self):
        """Every step is tried, one failing does not stop the others."""
        for f in reversed(self.undo):
            try:
                f()
            except Exception as e:  # noqa: BLE001 (report, and go on putting things back)
                print(f"bmfr: could not undo a render setting: {e}")
        for owner, name, value in self.saved:
            try:
                setattr(owner, name, value)
            except (AttributeError, TypeError):
                pass


def remove_row_properties(objects):
    for o in objects:
        for r in range(3):
            if f"{ROW_PROPERTY}{r}" in o:
                del o[f"{ROW_PROPERTY}{r}"]


def configure(scene, opts, state):
    render = scene.render
    if opts.width:
        render.resolution_x = opts.width
    if opts.height:
        render.resolution_y = opts.height
    render.resolution_percentage = 100
    if render.resolution_x <= 0 or render.resolution_y <= 0:
        raise SequenceError("zero image size")
    render.engine = "CYCLES"
    cycles = scene.cycles
    device = "CPU"
    cycles.device = "CPU"
    if opts.device == "GPU":
        device = use_gpu(scene, state)
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = opts.denoiser
    if opts.denoiser:
        cycles.denoiser = "OPENIMAGEDENOISE"
    cycles.filter_width = 0.01
    # Persistent data keeps the objects' properties of the first frame rendered, so the
    # previous-position AOV would go stale (Blender 3.4): on only where nothing moves.
    render.use_persistent_data = True
    settings = render.image_settings
    settings.file_format = "OPEN_EXR_MULTILAYER"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"
    render.use_file_extension = False
    layer = bpy.context.view_layer
    layer.use_pass_combined = True
    layer.use_pass_normal = True
    layer.use_pass_position = True
    layer.use_pass_emit = True
    layer.cycles.denoising_store_passes = True
    if opts.denoiser:
        layer.cycles.use_denoising = True
    # The other view layers are not rendered: each would put its own copy of every pass in the
    # files, and bmfr could not tell which to read.
    for other in scene.view_layers:
        if other != layer and other.use:
            other.use = False
            state.undo.append(lambda v=other: setattr(v, "use", True))
    return layer, device


def render_to(scene, path):
    """Renders into `path`, never leaving an earlier run's file there in its place."""
    if os.path.exists(path):
        os.remove(path)
    scene.render.filepath = path
    result = bpy.ops.render.render(write_still=True)
    if "FINISHED" not in result or not os.path.exists(path):
        raise SequenceError(f"Cycles did not write {path} ({', '.join(sorted(result))})")


def render_sequence(scene, out, opts, progress=None):
    """Renders scene's frames into the folder `out`. progress(done, total, text) is called after
    each frame. Returns a summary dict. Raises SequenceError for a scene it cannot render. The
    scene's own settings, materials and current frame are as they were afterwards."""
    check_scene(scene, opts)
    first, last = frame_range(scene, opts)
    state = SceneState(scene, bpy.context.view_layer)
    try:
        return render_frames(scene, out, opts, first, last, state, progress)
    finally:
        state.restore()
        scene.frame_set(scene.frame_current)


def shift_lens(cam, shift, jitter, w, h):
    """Moves the view by `jitter` pixels (y down) from the lens shift `shift`."""
    # Lens shift is in units of the larger image side; +x moves the view right and +y up.
    side = max(w, h)
    cam.data.shift_x = shift[0] + jitter[0] / side
    cam.data.shift_y = shift[1] - jitter[1] / side


def render_visibility(scene, out, first, jitters, layer, sun, frames, state, progress):
    """Each frame's visibility of `sun` through the frame's own jittered point, after the
    frames (one change of materials for all of them); entries are added to `frames`. The
    scene's changes go on state's undo list."""
    key_light.prepare(scene, sun, state.undo)
    w, h = scene.render.resolution_x, scene.render.resolution_y
    for n, jitter in enumerate(jitters):
        scene.frame_set(first + n)
        cam = scene.camera
        shift = (cam.data.shift_x, cam.data.shift_y)
        shift_lens(cam, shift, jitter, w, h)
        scene.cycles.seed = first + n
        name = f"visibility_{first + n:04d}.exr"
        try:
            render_to(scene, os.path.join(out, name))
        finally:
            cam.data.shift_x, cam.data.shift_y = shift
        frames[n]["visibility"] = {"file": name, "layer": f"{layer.name}.Combined"}
        if progress:
            progress(len(jitters), len(jitters), f"visibility {n + 1}/{len(jitters)}")


def render_frames(scene, out, opts, first, last, state, progress):
    layer, device = configure(scene, opts, state)
    render = scene.render
    moving = moving_objects(scene, first, last)
    motion = opts.motion == "on" or (opts.motion == "auto" and bool(moving))
    layer.use_pass_vector = motion
    render.use_persistent_data = not motion
    without_previous = []
    movers = []
    if motion:
        without_previous = add_previous_position_aov(scene, layer, state)
        movers = [o for o in scene.objects if o.type in GEOMETRY]
        state.undo.append(lambda: remove_row_properties(movers))
    out = os.path.abspath(out)
    os.makedirs(out, exist_ok=True)
    w, h = render.resolution_x, render.resolution_y
    frames = []
    doc = {"format": "bmfr-sequence", "version": 1, "width": w, "height": h,
           "color_is_demodulated": False,
           "generator": f"Blender {bpy.app.version_string} Cycles ({device}, {opts.spp} spp) via "
                        f"tools/blender/render_sequence.py; passes {PASS_NOTE}",
           "frames": frames}
    if motion:
        doc["motion_convention"] = "cycles"
    total = last - first
    previous_camera = None
    jitters = []
    for n, frame in enumerate(range(first, last)):
        if motion:
            set_previous_rows(scene, frame, movers)  # leaves the scene at `frame`
        else:
            scene.frame_set(frame)
        cam = scene.camera  # markers may switch cameras: a cut
        depsgraph = bpy.context.evaluated_depsgraph_get()
        shift = (cam.data.shift_x, cam.data.shift_y)
        vp = view_projection(cam, depsgraph, render)
        p0 = projection(cam, depsgraph, render)
        jitter = (halton(n + 1, 2) - 0.5, halton(n + 1, 3) - 0.5) if opts.jitter else (0.0, 0.0)
        shift_lens(cam, shift, jitter, w, h)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        p1 = projection(cam, depsgraph, render)
        realised = ((p1[0][2] - p0[0][2]) * w / 2, -(p1[1][2] - p0[1][2]) * h / 2)
        jitters.append(jitter)
        scene.cycles.samples = opts.spp
        scene.cycles.seed = opts.seed * 7919 + frame
        name = f"frame_{frame:04d}.exr"
        try:
            render_to(scene, os.path.join(out, name))
        finally:
            cam.data.shift_x, cam.data.shift_y = shift
        entry = {"color": name, "albedo": name, "normal": name, "position": name,
                 "emission": name, "view_projection": vp, "jitter": list(realised)}
        if previous_camera is not None and cam != previous_camera:
            entry["reset"] = True
        previous_camera = cam
        if motion:
            entry["motion"] = name
            entry["previous_position"] = {"file": name, "layer": f"{layer.name}.{PREVIOUS_AOV}"}
        if opts.reference_spp > 0:
            use_denoising = scene.cycles.use_denoising
            scene.cycles.use_denoising = False
            scene.cycles.samples = opts.reference_spp
            scene.cycles.seed = opts.seed * 7919 + frame + 1000003
            ref = f"reference_{frame:04d}.exr"
            try:
                render_to(scene, os.path.join(out, ref))
            finally:
                scene.cycles.use_denoising = use_denoising
            entry["reference"] = {"file": ref, "layer": f"{layer.name}.Combined"}
        frames.append(entry)
        write_json_atomically(os.path.join(out, "sequence.json"), doc)
        if progress:
            progress(n + 1, total, f"frame {n + 1}/{total} (Blender frame {frame})")
    sun = key_light.key_sun(scene, layer) if opts.visibility == "auto" else None
    if sun is not None:
        render_visibility(scene, out, first, jitters, layer, sun, frames, state, progress)
        doc["generator"] += f"; visibility of the sun '{sun.name}'"
        write_json_atomically(os.path.join(out, "sequence.json"), doc)
    return {"visibility": sun.name if sun else None,
            "output": out, "frames": total, "first": first, "width": w, "height": h,
            "device": device, "motion": motion, "moving": moving,
            "without_previous_position": without_previous}
