"""The tasks of a batch: each one run of `bmfr` (a part of a render, a denoise, a score), its
record of completion, and how a node runs it.

A task is finished when its record exists and matches: the record holds a digest of the task's
command and of what it read (the sequence's render fingerprint), and is written, atomically,
only after the command's outputs are all in. So a crashed or killed task is run again, and a
finished one is never redone. Plain data and the standard library only: a Ray worker runs
execute() on whatever node Ray picks.
"""
import ctypes
import hashlib
import json
import os
import shutil
import signal
import socket
import subprocess
import time

RENDER_FINGERPRINT = ".bmfr-render.json"  # written by bmfr render (render/sequence_renderer.h)
FRAME_RECORDS = ".bmfr-frames"  # a part's frame records (io/sequence.h)


class TaskFailed(Exception):
    """bmfr exited with an error: the same inputs fail the same way, so it is not retried."""


class TaskInterrupted(Exception):
    """bmfr was killed by a signal (a node shutting down, memory): worth another attempt."""


class StorageError(Exception):
    """This node cannot see the batch's output folder, or has no bmfr at the path given."""


def digest(*parts):
    return hashlib.sha256(json.dumps(parts, sort_keys=True).encode()).hexdigest()[:20]


def write_text_atomically(path, text):
    """Writes a temporary beside `path` (named for this node and process), syncs it and renames
    it over `path`: a reader sees the old file or the whole new one."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    temporary = f"{path}.{socket.gethostname()}-{os.getpid()}.part"  # unique across nodes
    with open(temporary, "w", encoding="utf-8", newline="") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(temporary, path)


def write_json_atomically(path, value):
    write_text_atomically(path, json.dumps(value, indent=1, sort_keys=True) + "\n")


def read_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def render_fingerprint(sequence_folder):
    """The fingerprint bmfr render wrote for the folder's scene and settings, or None."""
    found = read_json(os.path.join(sequence_folder, RENDER_FINGERPRINT))
    return found.get("fingerprint") if isinstance(found, dict) else None


def frames_in(sequence_folder, first, end):
    """True when frames [first, end) of a sequence rendered in parts are all recorded."""
    return all(os.path.isfile(os.path.join(sequence_folder, FRAME_RECORDS, f"{i:04d}.json"))
               for i in range(first, end))


def is_finished(task, fingerprint):
    """The task's record is there, is for this command and input, and its outputs exist."""
    record = read_json(task["record"])
    if not isinstance(record, dict) or record.get("key") != task["key"]:
        return False
    if fingerprint is None or record.get("input") != fingerprint:
        return False
    if "frames" in task and not frames_in(task["sequence"], *task["frames"]):
        return False
    return all(os.path.isfile(os.path.join(task["output"], f)) for f in task.get("expects", []))


try:  # resolved here, not after fork: the child of a threaded worker should only call it
    _PRCTL = ctypes.CDLL(None, use_errno=True).prctl
except (OSError, AttributeError):
    _PRCTL = None
PR_SET_PDEATHSIG = 1
# bmfr's message when another process holds the lock of the folder (or the part) it writes: on
# shared storage a crashed node's lock outlives it until the server's lease ends.
LOCK_HELD = "another run is writing to"
LOCK_WAIT_SECONDS = 180


def _die_with_parent():
    # bmfr goes down with the worker that started it: a killed worker leaves no render behind
    # writing into the folder its retry writes to.
    if _PRCTL is not None:
        _PRCTL(PR_SET_PDEATHSIG, signal.SIGKILL)


def execute(task, storage_token_path, storage_token, attempt_log=None, ray_node=""):
    """Runs one task on this node; returns what the driver reports. Raises TaskFailed,
    TaskInterrupted or StorageError."""
    node = socket.gethostname()
    try:
        with open(storage_token_path, encoding="utf-8") as f:
            seen = f.read()
    except OSError:
        seen = None
    if seen != storage_token:
        raise StorageError(
            f"node {node} cannot see the batch's output folder at "
            f"{os.path.dirname(os.path.dirname(storage_token_path))} (shared storage is assumed: "
            "mount it at the same path on every node)")
    if not os.access(task["argv"][0], os.X_OK):
        raise StorageError(f"node {node} has no bmfr at {task['argv'][0]} (install it at the same "
                           "path on every node, or on the shared storage)")
    if task.get("clear"):
        # A denoise or score without a matching record: whatever is there is stale or partial.
        shutil.rmtree(task["output"], ignore_errors=True)
    if attempt_log:
        with open(attempt_log, "a", encoding="utf-8") as log:
            log.write(json.dumps({"task": task["id"], "node": node, "pid": os.getpid(),
                                  "started": time.time()}) + "\n")
    start = time.monotonic()
    while True:
        run = subprocess.run(task["argv"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, preexec_fn=_die_with_parent, check=False)
        if LOCK_HELD not in run.stderr or time.monotonic() - start > LOCK_WAIT_SECONDS:
            break
        time.sleep(10)  # a lock left by a node that died: wait for it to expire
    seconds = time.monotonic() - start
    if run.returncode != 0:
        tail = (run.stderr.strip() or run.stdout.strip())[-2000:]
        command = " ".join(task["argv"])
        if run.returncode < 0:
            raise TaskInterrupted(f"{task['id']}: killed by signal {-run.returncode}: {command}")
        raise TaskFailed(f"{task['id']}: bmfr exited {run.returncode}: {command}\n{tail}")
    fingerprint = render_fingerprint(task["sequence"])
    write_json_atomically(task["record"], {
        "key": task["key"], "input": fingerprint, "task": task["id"], "node": node,
        "ray_node": ray_node, "seconds": round(seconds, 3),
        "command": task["argv"]})
    return {"id": task["id"], "node": node, "ray_node": ray_node, "seconds": seconds}
