"""A plan as tasks: each sequence rendered in parts of `chunk_frames` frames, denoised once per
method (its frames in order, after all of its parts), and scored once (after all of its
methods). The output folder holds:

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
            "--seed", str(seq.seed), "--bounces", str(seq.bounces), "--paths", seq.paths,
            "--frame-range", f"{first}:{end}", "--threads", str(plan.cpus_per_task),
            # The batch owns this folder: a plan whose sequence changed replaces it.
            "--overwrite", "-q", "-o", output]
    if seq.reference_samples == 0:
        argv.insert(-4, "--no-reference")
    return argv


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
    tasks = []
    for seq in plan.sequences:
        folder = os.path.join(out, "sequences", seq.name)
        renders = []
        for first in range(0, seq.frames, plan.chunk_frames):
            end = min(seq.frames, first + plan.chunk_frames)
            argv = _render_argv(bmfr, plan, seq, first, end, folder)
            tid = f"render/{seq.name}/{first:04d}-{end:04d}"
            tasks.append({"id": tid, "kind": "render", "argv": argv, "sequence": folder,
                          "output": folder, "frames": [first, end], "deps": [],
                          "key": digest(argv[1:]),
                          "cost": seq.width * seq.height * (end - first) *
                          (seq.reference_samples + 4),
                          "record": os.path.join(records, tid.replace("/", "_") + ".json")})
            renders.append(tasks[-1])
        methods = []
        for method in plan.methods:
            output = os.path.join(out, "runs", seq.name, method.name)
            argv = _method_argv(bmfr, plan, method, folder, output)
            tid = f"denoise/{seq.name}/{method.name}"
            tasks.append({"id": tid, "kind": "denoise", "argv": argv, "sequence": folder,
                          "output": output, "clear": True, "expects": ["report.json"],
                          "deps": [r["id"] for r in renders],
                          "key": digest(argv[1:], [r["key"] for r in renders]),
                          "cost": seq.width * seq.height * seq.frames * (400 if method.peer else 8),
                          "record": os.path.join(records, tid.replace("/", "_") + ".json")})
            methods.append(tasks[-1])
        if seq.reference_samples == 0:
            continue  # nothing to score against
        output = os.path.join(out, "scores", seq.name)
        argv = [bmfr, "eval", "-r", folder, "-m", "noisy"]
        for method, run in zip(plan.methods, methods):
            argv += ["-m", f"{method.name}={run['output']}"]
        argv += ["-o", output, "-q"]
        if "flip" not in plan.metrics:
            argv.append("--no-flip")
        tid = f"score/{seq.name}"
        tasks.append({"id": tid, "kind": "score", "argv": argv, "sequence": folder,
                      "output": output, "clear": True, "expects": ["table.json", "report.html"],
                      "deps": [m["id"] for m in methods],
                      "key": digest(argv[1:], [m["key"] for m in methods]),
                      "cost": seq.width * seq.height * seq.frames * 4 * (len(methods) + 1),
                      "record": os.path.join(records, tid.replace("/", "_") + ".json")})
    return tasks
