"""Runs a plan's tasks on Ray: the tasks not already finished are submitted with their
dependencies, each declaring its CPUs; a task whose worker dies is retried by Ray, one whose bmfr
was killed by a signal is retried too, one whose bmfr exited with an error is not (it would fail
again). Progress shows tasks done, running and failed, and the time left."""
import fcntl
import logging
import os
import re
import secrets
import socket
import subprocess
import sys
import time

from . import tables
from .graph import build_tasks
from .plan import PlanError
from .tasks import (StorageError, TaskFailed, TaskInterrupted, execute, is_finished,
                    render_fingerprint, write_json_atomically)

# What a killed writer leaves: bmfr's "<file>.<pid>-<n>.part" and this package's
# "<file>.<pid>.part". Never mistaken for outputs, removed once nothing runs.
PARTIAL = re.compile(r"\.\d+(-\d+)?\.part$")


class BatchError(Exception):
    """The batch cannot start or did not finish: the message says why."""


def _connect(cluster, package_dir):
    if cluster not in ("auto", "local"):
        _check_reachable(cluster)
    elif cluster == "auto" and os.environ.get("RAY_ADDRESS"):
        _check_reachable(os.environ["RAY_ADDRESS"])
    import ray  # here, so that plan and address errors are reported without Ray installed

    options = {"include_dashboard": False, "logging_level": logging.WARNING,
               "log_to_driver": False,
               # The workers import this package from the driver's copy, on every node.
               "runtime_env": {"py_modules": [package_dir]}}
    if cluster == "auto":
        # An address that is given and wrong is an error, never a study run here instead.
        address = "auto" if os.environ.get("RAY_ADDRESS") else None
    else:
        address = cluster
    try:
        if address is None:
            try:
                ray.init(address="auto", **options)
            except ConnectionError:  # no cluster on this machine: start one
                ray.init(address="local", **options)
        else:
            ray.init(address=address, **options)
    except Exception as e:  # Ray's errors for a wrong address, a token, versions, a start
        where = {"local": "start Ray on this machine"}.get(
            cluster, f"join the Ray cluster at {os.environ.get('RAY_ADDRESS') or cluster}")
        detail = str(e).strip().splitlines()[-1] if str(e).strip() else type(e).__name__
        raise BatchError(f"cannot {where}: {detail}") from None
    return ray


def _check_reachable(address):
    """Ray retries an address that nothing answers for minutes: say so at once."""
    host, _, port = address.replace("ray://", "").rpartition(":")
    if not host or not port.isdigit():
        raise BatchError(f"--cluster {address}: not HOST:PORT (the head node's address)")
    try:
        socket.create_connection((host, int(port)), timeout=10).close()
    except OSError as e:
        raise BatchError(f"no Ray head node answers at {address} ({e.strerror or e}); start one "
                         "with `ray start --head`, or leave --cluster out to run on this "
                         "machine") from None


def _check_resources(ray, plan, tasks):
    """A task that asks more CPUs than any node has, or a GPU where none has one, would wait for
    ever."""
    nodes = [n.get("Resources", {}) for n in ray.nodes() if n.get("Alive")]
    largest = max((n.get("CPU", 0) for n in nodes), default=0)
    if plan.cpus_per_task > largest:
        raise BatchError(f"the plan's cpus_per_task = {plan.cpus_per_task}, but the largest node "
                         f"of the cluster has {largest:g} CPUs: no task could start")
    cuda = [t["id"] for t in tasks if t.get("gpus")]
    if cuda and not any(n.get("GPU", 0) >= 1 for n in nodes):
        raise BatchError(f"{cuda[0]} runs on CUDA, but no node of the cluster has a GPU")


def _lock(out):
    os.makedirs(os.path.join(out, ".batch"), exist_ok=True)
    fd = os.open(os.path.join(out, ".batch", "lock"), os.O_RDWR | os.O_CREAT, 0o644)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        raise BatchError(f"another bmfr batch is running into {out}; wait for it or give "
                         "another output folder") from None
    return fd


def _check_output_folder(out):
    if os.path.exists(out) and not os.path.isdir(out):
        raise BatchError(f"{out} exists and is not a folder")
    if os.path.isdir(out) and os.listdir(out) and not os.path.isfile(
            os.path.join(out, ".batch", "plan.json")):
        raise BatchError(f"{out} is not empty and holds no earlier batch (no .batch/plan.json); "
                         "refusing to write into it. Give an empty or new folder, or an earlier "
                         "batch's to resume it")


def _remove_partial_files(out):
    for root, _, files in os.walk(out):
        for name in files:
            if PARTIAL.search(name):
                try:
                    os.remove(os.path.join(root, name))
                except OSError:
                    pass


class Progress:
    """A line rewritten in place on a terminal; a line every 10 s otherwise."""

    def __init__(self, total, quiet):
        self.total, self.quiet = total, quiet
        self.tty = sys.stderr.isatty()
        self.last = 0.0
        self.start = time.monotonic()

    def show(self, done, skipped, running, failed, retried, cost_done, cost_left, final=False):
        if self.quiet:
            return
        now = time.monotonic()
        if not final and not self.tty and now - self.last < 10:
            return
        self.last = now
        elapsed = now - self.start
        eta = ""
        if cost_done > 0 and cost_left > 0:
            eta = f", about {elapsed * cost_left / cost_done:.0f} s left"
        line = (f"bmfr batch: {done + skipped}/{self.total} tasks done ({skipped} finished "
                f"earlier), {running} running, {failed} failed, {retried} retried{eta}")
        if self.tty:
            sys.stderr.write("\r" + line.ljust(100) + ("\n" if final else ""))
        else:
            sys.stderr.write(line + "\n")
        sys.stderr.flush()


def _attempts(path):
    """Task id -> attempts started, from the attempts log the workers append to."""
    counts = {}
    try:
        with open(path, encoding="utf-8") as f:
            for line in f:
                tid = line.split('"task": "', 1)[-1].split('"', 1)[0]
                counts[tid] = counts.get(tid, 0) + 1
    except OSError:
        pass
    return counts


def run_batch(plan, out, bmfr, cluster="auto", retries=3, quiet=False):
    """Runs `plan` into `out`; returns (rows of the table, summary dict). Raises BatchError."""
    out = os.path.abspath(out)
    check_presets(plan, bmfr)
    _check_output_folder(out)
    lock = _lock(out)
    try:
        return _run_locked(plan, out, bmfr, cluster, retries, quiet)
    finally:
        os.close(lock)


def check_presets(plan, bmfr):
    """Every scene that is not a file is one of bmfr render's presets."""
    listed = subprocess.run([bmfr, "render", "--list-presets"], capture_output=True, text=True)
    if listed.returncode != 0:
        raise BatchError(f"{bmfr} render --list-presets failed: {listed.stderr.strip()}")
    presets = {parts[0] for parts in map(str.split, listed.stdout.splitlines())
               if len(parts) > 1 and re.fullmatch(r"\d+x\d+", parts[1])}
    for seq in plan.sequences:
        if not seq.scene.endswith(".json") and seq.scene not in presets:
            raise PlanError(f"sequence '{seq.name}': scene '{seq.scene}' is neither a preset "
                            f"({', '.join(sorted(presets))}) nor a "
                            "scene description .json")


def _run_locked(plan, out, bmfr, cluster, retries, quiet):
    tasks = build_tasks(plan, bmfr, out)
    fingerprints = {t["sequence"]: render_fingerprint(t["sequence"]) for t in tasks}
    finished = {t["id"] for t in tasks if is_finished(t, fingerprints[t["sequence"]])}
    # A task below one that runs again runs again too (its inputs are being remade).
    by_id = {t["id"]: t for t in tasks}
    for t in tasks:
        if any(d not in finished for d in t["deps"]):
            finished.discard(t["id"])
    to_run = [t for t in tasks if t["id"] not in finished]
    batch = os.path.join(out, ".batch")
    token = secrets.token_hex(16)
    token_path = os.path.join(batch, "storage-token")
    write_json_atomically(os.path.join(batch, "plan.json"),
                          {"tasks": [{k: t[k] for k in ("id", "argv", "deps")} for t in tasks]})
    with open(token_path, "w", encoding="utf-8") as f:
        f.write(token)
    attempts_path = os.path.join(batch, "attempts.log")
    open(attempts_path, "w").close()
    start = time.monotonic()
    summary = {"tasks": len(tasks), "run": len(to_run), "skipped": len(finished), "failed": [],
               "retried": 0, "nodes": [], "seconds": 0.0}
    progress = Progress(len(tasks), quiet)
    if to_run:
        ray = _connect(cluster, os.path.dirname(os.path.abspath(__file__)))
        try:
            _check_resources(ray, plan, to_run)
            summary.update(_submit(ray, to_run, by_id, finished, retries, plan, token_path,
                                   token, attempts_path, progress))
        finally:
            ray.shutdown()
    else:
        progress.show(0, len(finished), 0, 0, 0, 0, 0, final=True)
    _remove_partial_files(out)
    summary["seconds"] = time.monotonic() - start
    rows = tables.gather(plan, out)
    return rows, summary


def _submit(ray, to_run, by_id, finished, retries, plan, token_path, token, attempts_path,
            progress):
    @ray.remote(max_retries=retries, retry_exceptions=[TaskInterrupted])
    def run_one(task, *deps):
        node = ray.get_runtime_context().get_node_id()
        return execute(task, token_path, token, attempts_path, node)

    refs = {}
    for t in to_run:  # dependencies first (build_tasks' order)
        deps = [refs[d] for d in t["deps"] if d in refs]
        refs[t["id"]] = run_one.options(num_cpus=plan.cpus_per_task, num_gpus=t.get("gpus", 0),
                                        name=t["id"]).remote(t, *deps)
    pending = {ref: tid for tid, ref in refs.items()}
    done, failed, nodes = set(), [], set()
    cost_total = sum(by_id[tid]["cost"] for tid in refs)
    cost_done = 0
    while pending:
        ready, _ = ray.wait(list(pending), num_returns=1, timeout=1.0)
        for ref in ready:
            tid = pending.pop(ref)
            try:
                result = ray.get(ref)
                done.add(tid)
                nodes.add(f"{result['node']} ({result['ray_node'][:8]})")
                cost_done += by_id[tid]["cost"]
            except ray.exceptions.RayTaskError as e:
                cause = e.cause if hasattr(e, "cause") else e
                # Ray hands pending refs back in the order given (dependencies first), so a
                # dependency not done by now has failed.
                if any(d not in done and d in refs for d in by_id[tid]["deps"]):
                    failed.append(f"{tid}: not run, as a task it needs failed")
                elif isinstance(cause, (TaskFailed, TaskInterrupted, StorageError)):
                    failed.append(f"{tid}: {cause}")
                else:
                    failed.append(f"{tid}: {str(e).strip().splitlines()[-1]}")
            except ray.exceptions.RayError as e:  # the worker died on every attempt
                if any(d not in done and d in refs for d in by_id[tid]["deps"]):
                    failed.append(f"{tid}: not run, as a task it needs failed")
                    continue
                failed.append(f"{tid}: {type(e).__name__}: {str(e).strip().splitlines()[0]}")
        attempts = _attempts(attempts_path)
        started = {tid for tid in attempts if tid in refs}
        running = len(started - done - {f.split(":")[0] for f in failed})
        retried = sum(n - 1 for n in attempts.values() if n > 1)
        progress.show(len(done), len(finished), running, len(failed), retried, cost_done,
                      cost_total - cost_done, final=not pending)
    attempts = _attempts(attempts_path)
    return {"failed": failed, "retried": sum(n - 1 for n in attempts.values() if n > 1),
            "nodes": sorted(nodes)}
