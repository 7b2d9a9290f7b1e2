"""A plan as tasks: each sequence rendered in parts of `chunk_frames` frames, then assembled
(its sequence.json written, once every part is in: on shared storage the last part may not see
the others' files yet), denoised once per method (its frames in order) and scored once (after
all of its methods). The output folder holds:

    sequences/SEQ/          the rendered sequence (bmfr render, in parts)
    runs/SEQ/METHOD/        bmfr denoise (or bmfr peer) outputs
    scores/SEQ/             bmfr eval's report of every method on SEQ
    results.csv, results.json, index.html
    .batch/                 the records of finished tasks, the attempts log, the lock
"""
import os

from .tasks import digest


def _render_argv(bmfr, plan, seq, first, end, output):
    argv = [bmfr, "render", "-s", seq.scene, "--scenes", plan.scenes,
            "--width", str(seq.width), "--height", str(seq.height),
            "--frames", str(seq.frames), "--reference-spp", str(seq.reference_samples),
            "--paths", seq.paths, "--frame-range", f"{first}:{end}",
            "--threads", str(plan.cpus_per_task),
            # The batch owns this folder: a plan whose sequence changed replaces it. A plan of
            # day-long references is what a batch is for: no estimate stops a part.
            "--overwrite", "--yes", "-q", "-o", output]
    if seq.seed is not None:  # else the scene's own
        argv[2:2] = ["--seed", str(seq.seed)]
    if seq.bounces is not None:
        argv[2:2] = ["--bounces", str(seq.bounces)]
    if seq.reference_samples == 0:
        argv[2:2] = ["--no-reference"]
    return argv


def _key(argv, out, *more):
    """What a task's output depends on: its command without the executable, the threads it was
    given or where OUT is mounted, plus `more`."""
    kept, skip = [], False
    for a in argv[1:]:
        if skip:
            skip = False
            continue
        if a == "--threads":
            skip = True
            continue
        kept.append(a.replace(out, "$OUT"))
    return digest(kept, *more)


def _scene_contents(seq):
    """A scene description's bytes, so that an edited one is rendered again."""
    if not seq.scene.endswith(".json"):
        return ""
    with open(seq.scene, "rb") as f:
        return digest(f.read().decode("utf-8", errors="replace"))


def _setting(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def _method_argv(bmfr, plan, method, sequence, output):
    if method.peer:
        argv = [bmfr, "peer", method.filter, sequence, "-o", output, "--threads",
                str(plan.cpus_per_task)]
    else:
        argv = [bmfr, "denoise", sequence, "-o", output, "--filter", method.filter,
                "--threads", str(plan.cpus_per_task)]
        if method.preset:
            argv += ["--preset", method.preset]
        if method.backend:
            argv += ["--backend", method.backend]
    for key in sorted(method.settings):
        # A peer's settings are its own options (bmfr peer oidn --quality high).
        argv += ([f"--{key}", _setting(method.settings[key])] if method.peer else
                 ["--set", f"{key}={_setting(method.settings[key])}"])
    return argv + ["--no-flip", "-q"]


def build_tasks(plan, bmfr, out):
    """The tasks of `plan` in an order that runs dependencies first (no score for a sequence
    without a reference). Each task is a plain dict:
    id, kind, argv, sequence, output, record, key, deps (task ids), and for renders the frames,
    for the rest the files that say its outputs are in (expects)."""
    records = os.path.join(out, ".batch", "records")

    def task(tid, kind, argv, folder, output, deps, key, cost, **more):
        tasks.append(dict(id=tid, kind=kind, argv=argv, sequence=folder, output=output, deps=deps,
                          key=key, cost=cost,
                          record=os.path.join(records, tid.replace("/", "_") + ".json"), **more))
        return tasks[-1]

    tasks = []
    for seq in plan.sequences:
        folder = os.path.join(out, "sequences", seq.name)
        pixels = seq.width * seq.height
        scene = _scene_contents(seq)
        parts = []
        for first in range(0, seq.frames, plan.chunk_frames):
            end = min(seq.frames, first + plan.chunk_frames)
            argv = _render_argv(bmfr, plan, seq, first, end, folder)
            parts.append(task(f"render/{seq.name}/{first:04d}-{end:04d}", "render", argv, folder,
                              folder, [], _key(argv, out, scene),
                              pixels * (end - first) * (seq.reference_samples + 4),
                              frames=[first, end]))
        # The whole range: every frame is on disk, so it only writes sequence.json.
        argv = _render_argv(bmfr, plan, seq, 0, seq.frames, folder)
        whole = task(f"assemble/{seq.name}", "assemble", argv, folder, folder,
                     [p["id"] for p in parts], _key(argv, out, scene, [p["key"] for p in parts]),
                     pixels, expects=["sequence.json"], frames=[0, seq.frames])
        methods = []
        for method in plan.methods:
            output = os.path.join(out, "runs", seq.name, method.name)
            argv = _method_argv(bmfr, plan, method, folder, output)
            methods.append(task(f"denoise/{seq.name}/{method.name}", "denoise", argv, folder,
                                output, [whole["id"]], _key(argv, out, whole["key"]),
                                pixels * seq.frames * (400 if method.peer else 8), clear=True,
                                expects=["report.json"],
                                gpus=1 if method.backend == "cuda" else 0))
        if seq.reference_samples == 0:
            continue  # nothing to score against
        output = os.path.join(out, "scores", seq.name)
        argv = [bmfr, "eval", "-r", folder, "-m", "noisy"]
        for method, run in zip(plan.methods, methods):
            argv += ["-m", f"{method.name}={run['output']}"]
        argv += ["-o", output, "-q"]
        if "flip" not in plan.metrics:
            argv.append("--no-flip")
        task(f"score/{seq.name}", "score", argv, folder, output, [m["id"] for m in methods],
             _key(argv, out, [m["key"] for m in methods]),
             pixels * seq.frames * 4 * (len(methods) + 1), clear=True,
             expects=["table.json", "report.html"])
    return tasks
