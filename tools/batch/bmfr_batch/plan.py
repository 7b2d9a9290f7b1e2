"""A batch plan: the sequences to render, the methods to run on each and the metrics to gather.

The plan is JSON (docs/batch.md). Every mistake in it is a PlanError that names the entry and
the key, before anything runs.
"""
import json
import os
import re
from dataclasses import dataclass, field

METRICS = ["rmse", "psnr_db", "ssim", "flip", "relmse", "temporal_error", "temporal_change_error"]
FILTERS = ["bmfr", "svgf", "walr", "mara2017"]
PEERS = ["oidn"]
NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]{0,63}$")


class PlanError(Exception):
    """A plan that cannot run: the message says which entry and key, and why."""


@dataclass
class Sequence:
    name: str
    scene: str  # a preset name, or a scene description JSON (absolute path)
    width: int
    height: int
    frames: int
    reference_samples: int
    seed: object = None  # None: the scene's own
    bounces: object = None
    paths: str = "bmfr"


@dataclass
class Method:
    name: str
    filter: str = "bmfr"  # or the peer's name, for a peer
    peer: bool = False
    preset: str = ""
    backend: str = ""  # cpu, reference or cuda; "" = bmfr's default (cpu)
    settings: dict = field(default_factory=dict)


@dataclass
class Plan:
    sequences: list
    methods: list
    metrics: list
    scenes: str  # the folder holding the presets' meshes (absolute)
    chunk_frames: int = 4
    cpus_per_task: int = 1


def _check_keys(entry, allowed, where):
    if not isinstance(entry, dict):
        raise PlanError(f"{where} must be an object, got {json.dumps(entry)}")
    for key in entry:
        if key not in allowed:
            raise PlanError(f"{where}: unknown key '{key}' (keys: {', '.join(allowed)})")


def _integer(entry, key, where, low, high, default=None):
    value = entry.get(key, default)
    if value is None:
        raise PlanError(f"{where}: '{key}' is required")
    if not isinstance(value, int) or isinstance(value, bool) or not low <= value <= high:
        raise PlanError(f"{where}: '{key}' = {json.dumps(value)} must be an integer in "
                        f"[{low}, {high}]")
    return value


def _name(entry, where, seen):
    name = entry.get("name")
    if not isinstance(name, str) or not NAME.match(name):
        raise PlanError(f"{where}: 'name' = {json.dumps(name)} must be 1-64 letters, digits, "
                        "'.', '_' or '-' (it names a folder)")
    if name in seen:
        raise PlanError(f"{where}: the name '{name}' is used twice")
    seen.add(name)
    return name


def _sequence(entry, where, base, seen):
    _check_keys(entry, ["name", "scene", "width", "height", "frames", "samples",
                        "reference_samples", "seed", "bounces", "paths"], where)
    name = _name(entry, where, seen)
    scene = entry.get("scene")
    if not isinstance(scene, str) or not scene:
        raise PlanError(f"{where}: 'scene' must be a preset name (bmfr render --list-presets) "
                        "or a scene description JSON")
    if scene.endswith(".json"):
        scene = os.path.normpath(os.path.join(base, scene))
        if not os.path.isfile(scene):
            raise PlanError(f"{where}: scene description {scene} does not exist")
    if entry.get("samples", 1) != 1:
        raise PlanError(f"{where}: 'samples' = {json.dumps(entry['samples'])}: bmfr render's "
                        "input is 1 sample per pixel, the input the filters are for")
    paths = entry.get("paths", "bmfr")
    if paths not in ("bmfr", "mara"):
        raise PlanError(f"{where}: 'paths' = {json.dumps(paths)} must be bmfr or mara")
    return Sequence(name=name, scene=scene,
                    width=_integer(entry, "width", where, 1, 16384),
                    height=_integer(entry, "height", where, 1, 16384),
                    frames=_integer(entry, "frames", where, 1, 100000),
                    reference_samples=_integer(entry, "reference_samples", where, 0, 1 << 20),
                    seed=(_integer(entry, "seed", where, 0, 2**32 - 1)
                          if "seed" in entry else None),
                    bounces=_integer(entry, "bounces", where, 0, 64) if "bounces" in entry else None,
                    paths=paths)


def _method(entry, where, seen):
    _check_keys(entry, ["name", "filter", "peer", "preset", "backend", "set"], where)
    name = _name(entry, where, seen)
    if name == "noisy":
        raise PlanError(f"{where}: 'noisy' is the input's own row; give the method another name")
    if "peer" in entry:
        if entry["peer"] not in PEERS or "filter" in entry or "preset" in entry:
            raise PlanError(f"{where}: 'peer' must be one of {', '.join(PEERS)}, without "
                            "'filter' or 'preset'")
        kind, peer = entry["peer"], True
    else:
        kind, peer = entry.get("filter", "bmfr"), False
        if kind not in FILTERS:
            raise PlanError(f"{where}: 'filter' = {json.dumps(kind)} must be one of "
                            f"{', '.join(FILTERS)}")
    preset = entry.get("preset", "")
    if preset not in ("", "faithful", "quality"):
        raise PlanError(f"{where}: 'preset' = {json.dumps(preset)} must be faithful or quality")
    backend = entry.get("backend", "")
    if backend not in ("", "cpu", "reference", "cuda") or (backend and peer):
        raise PlanError(f"{where}: 'backend' = {json.dumps(backend)} must be cpu, reference or "
                        "cuda, for a filter")
    settings = entry.get("set", {})
    if not isinstance(settings, dict) or not all(
            isinstance(v, (int, float, str, bool)) for v in settings.values()):
        raise PlanError(f"{where}: 'set' must map setting keys (bmfr settings FILTER) to "
                        "numbers, strings or booleans")
    return Method(name=name, filter=kind, peer=peer, preset=preset, backend=backend,
                  settings=settings)


def parse_plan(text, base, source="the plan"):
    """Parses plan JSON `text`; relative paths in it are relative to the folder `base`."""
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as e:
        raise PlanError(f"{source}: not JSON: {e}") from None
    _check_keys(doc, ["sequences", "methods", "metrics", "scenes", "chunk_frames",
                      "cpus_per_task"], source)
    for key in ("sequences", "methods"):
        if not isinstance(doc.get(key), list) or not doc[key]:
            raise PlanError(f"{source}: '{key}' must be a list of at least one entry")
    names = set()
    sequences = [_sequence(e, f"{source}: sequences[{i}]", base, names)
                 for i, e in enumerate(doc["sequences"])]
    names = set()
    methods = [_method(e, f"{source}: methods[{i}]", names) for i, e in enumerate(doc["methods"])]
    metrics = doc.get("metrics", METRICS)
    if not isinstance(metrics, list) or not metrics or any(m not in METRICS for m in metrics):
        raise PlanError(f"{source}: 'metrics' = {json.dumps(metrics)} must list some of "
                        f"{', '.join(METRICS)}")
    scenes = doc.get("scenes", "../shared/scenes")
    if not isinstance(scenes, str):
        raise PlanError(f"{source}: 'scenes' must be a folder")
    return Plan(sequences=sequences, methods=methods, metrics=list(metrics),
                scenes=os.path.normpath(os.path.join(base, scenes)),
                chunk_frames=_integer(doc, "chunk_frames", source, 1, 100000, 4),
                cpus_per_task=_integer(doc, "cpus_per_task", source, 1, 1024, 1))


def load_plan(path):
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        raise PlanError(f"cannot read the plan {path}: {e.strerror}") from None
    except UnicodeDecodeError as e:
        raise PlanError(f"{path}: not UTF-8 text ({e.reason} at byte {e.start})") from None
    return parse_plan(text, os.path.dirname(os.path.abspath(path)), path)
