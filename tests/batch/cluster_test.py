"""bmfr batch on a real two-node Ray cluster on this machine.

Starts a head node and a second node on loopback, runs a plan of four tiny sequences across both,
kills the Ray worker of one render part mid-render, and checks that the batch still completes,
that both nodes ran tasks, that a second run recomputes nothing, and that the outputs equal those
of the same plan run on one machine. Stops the cluster (its own processes only) at the end.

    python cluster_test.py BMFR WORK      (the Python that has Ray; exit 77: no Ray, skipped)
"""
import csv
import filecmp
import json
import os
import shutil
import signal
import subprocess
import sys
import time

BMFR, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
DEADLINE = time.monotonic() + 540
HEAVY = "lamp"  # the sequence whose render part is killed: its parts take seconds
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                                "batch"))
from bmfr_batch.local_cluster import LocalCluster  # noqa: E402


def fail(message):
    print(f"FAIL: {message}", flush=True)
    sys.exit(1)


PLAN = {
    "sequences": [
        {"name": "box", "scene": "cornell-moving", "width": 40, "height": 30, "frames": 4,
         "reference_samples": 32},
        {"name": "objects", "scene": "cornell-objects", "width": 40, "height": 30, "frames": 4,
         "reference_samples": 32},
        {"name": "moving", "scene": "cornell-objects-moving", "width": 40, "height": 30,
         "frames": 4, "reference_samples": 32, "seed": 5},
        {"name": HEAVY, "scene": "room-light", "width": 64, "height": 48, "frames": 4,
         "reference_samples": 768},
    ],
    "methods": [{"name": "bmfr", "filter": "bmfr"},
                {"name": "svgf", "filter": "svgf", "set": {"taa": False}}],
    "metrics": ["rmse", "ssim", "temporal_error", "temporal_change_error"],
    "chunk_frames": 2,
}
# Per sequence: its parts, the assembly of its manifest, a denoise per method, a score.
TASKS = sum(-(-q["frames"] // PLAN["chunk_frames"]) + 1 + len(PLAN["methods"]) + 1
            for q in PLAN["sequences"])


def processes():
    """pid -> (parent pid, command line) of every process."""
    found = {}
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                line = f.read().replace(b"\0", b" ").decode(errors="replace")
            with open(f"/proc/{pid}/stat") as f:
                parent = int(f.read().rsplit(")", 1)[1].split()[1])
        except (OSError, ValueError, IndexError):
            continue
        found[int(pid)] = (parent, line)
    return found


def run_batch(out, cluster, env, kill_one=False):
    """Runs the plan; with kill_one, SIGKILLs the Ray worker running a part of HEAVY's render
    once it is under way. Returns (stdout+stderr, the killed task's frame range or None)."""
    argv = [BMFR, "batch", os.path.join(WORK, "plan.json"), "-o", out, "--cluster", cluster,
            "--python", sys.executable]
    batch = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                             env=env)
    killed = None
    target = os.path.join(out, "sequences", HEAVY)
    seen_at = {}
    while kill_one and killed is None and batch.poll() is None:
        for pid, (parent, line) in processes().items():
            if " render " in line and "--frame-range" in line and target in line:
                seen_at.setdefault(pid, time.monotonic())
                if time.monotonic() - seen_at[pid] > 0.7:  # mid-render, a frame or so in
                    worker = processes().get(parent, (0, ""))[1]
                    if "ray" not in worker.lower():
                        fail(f"the render's parent is not a Ray worker: {worker}")
                    killed = line.split("--frame-range ")[1].split()[0]
                    os.kill(parent, signal.SIGKILL)
                    print(f"killed Ray worker {parent} (running frames {killed} of {HEAVY})",
                          flush=True)
                    break
        time.sleep(0.05)
    try:
        output, _ = batch.communicate(timeout=max(10, DEADLINE - time.monotonic()))
    except subprocess.TimeoutExpired:
        batch.kill()
        fail("the batch did not finish in time")
    if batch.returncode != 0:
        fail(f"bmfr batch exited {batch.returncode}:\n{output}")
    return output, killed


def quality_rows(out):
    with open(os.path.join(out, "results.csv"), newline="") as f:
        return [{k: v for k, v in row.items() if k not in ("ms_per_frame", "machine")}
                for row in csv.DictReader(f)]


def output_files(out):
    """Relative paths of the files that must match between runs: the sequences and the denoised
    frames (not the lock files, the timings in reports or the batch's own records)."""
    found = []
    for root, _, files in os.walk(out):
        rel = os.path.relpath(root, out)
        if rel == "." or rel.startswith(".batch") or rel.startswith("scores"):
            continue  # the tables hold timings: their scores are compared by quality_rows
        for name in files:
            if name.startswith(".bmfr-lock") or name in ("report.json", ".bmfr-render.json"):
                continue
            if rel.startswith("runs") and not name.endswith((".exr", ".png")):
                continue
            found.append(os.path.join(rel, name))
    return sorted(found)


def mtimes(out):
    tables = ["results.csv", "results.json", "index.html"]
    return {f: os.stat(os.path.join(out, f)).st_mtime_ns for f in output_files(out) + tables}


def main():
    try:
        import ray  # noqa: F401
    except ImportError:
        if os.environ.get("CI"):
            fail(f"Ray is not installed for {sys.executable} (scripts/install-ray.sh)")
        print("skipped: Ray is not installed (scripts/install-ray.sh)")
        sys.exit(77)
    signal.signal(signal.SIGTERM, lambda *_: fail("stopped by SIGTERM"))  # stop the cluster too
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    with open(os.path.join(WORK, "plan.json"), "w") as f:
        json.dump(PLAN, f)
    on_cluster, on_one = os.path.join(WORK, "cluster"), os.path.join(WORK, "one")
    cluster = LocalCluster([1, 1], WORK)
    try:
        t = time.monotonic()
        cluster.start()
        print(f"two nodes up at {cluster.address} in {time.monotonic() - t:.1f} s", flush=True)
        t = time.monotonic()
        output, killed = run_batch(on_cluster, cluster.address, cluster.env, kill_one=True)
        print(f"plan on two nodes, one worker killed: {time.monotonic() - t:.1f} s", flush=True)
        print(output.strip().splitlines()[-2], flush=True)
        if killed is None:
            fail("no render part of the heavy sequence was seen running")
        attempts = [json.loads(line) for line in
                    open(os.path.join(on_cluster, ".batch", "attempts.log"))]
        first, end = (int(x) for x in killed.split(":"))
        tid = f"render/{HEAVY}/{first:04d}-{end:04d}"
        if sum(a["task"] == tid for a in attempts) < 2:
            fail(f"the killed task {tid} was not run again: {attempts}")
        records = [json.load(open(os.path.join(on_cluster, ".batch", "records", r)))
                   for r in os.listdir(os.path.join(on_cluster, ".batch", "records"))]
        if len(records) != TASKS:
            fail(f"{len(records)} task records, expected {TASKS}")
        ray_nodes = {r["ray_node"] for r in records}
        if len(ray_nodes) != 2:
            fail(f"the tasks ran on {len(ray_nodes)} node(s), expected both")
        leftovers = [os.path.join(r, n) for r, _, ns in os.walk(on_cluster) for n in ns
                     if n.endswith(".part")]
        if leftovers:
            fail(f"half-written files left behind: {leftovers}")

        before = mtimes(on_cluster)
        again, _ = run_batch(on_cluster, cluster.address, cluster.env)
        if f"0 task(s) run, {TASKS} finished earlier" not in again:
            fail(f"the second run recomputed something:\n{again}")
        after = mtimes(on_cluster)
        if after != before:
            fail("the second run rewrote outputs: " +
                 ", ".join(f for f in after if before.get(f) != after[f])[:500])
        print("second run: nothing recomputed", flush=True)
    finally:
        cluster.stop()
    t = time.monotonic()
    run_batch(on_one, "local", cluster.env)
    print(f"plan on one local node: {time.monotonic() - t:.1f} s", flush=True)
    files = output_files(on_one)
    if files != output_files(on_cluster):
        fail("the two runs wrote different files")
    _, mismatch, errors = filecmp.cmpfiles(on_one, on_cluster, files, shallow=False)
    if mismatch or errors:
        fail(f"files differ between the cluster's and one machine's runs: {mismatch + errors}")
    if quality_rows(on_one) != quality_rows(on_cluster):
        fail("the scores differ between the cluster's and one machine's runs")
    print(f"{len(files)} files and {len(quality_rows(on_one))} score rows equal a single-machine "
          "run's")
    print("batch cluster test passed")


if __name__ == "__main__":
    main()
