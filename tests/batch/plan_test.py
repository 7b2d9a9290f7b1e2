"""bmfr batch without a cluster: plan mistakes are clear errors (exit 2) naming the entry and
key, a folder that is not a batch's is refused (exit 1), and a plan becomes the tasks the
cluster runs (parts of renders, then denoises, then a score per sequence).

    python3 plan_test.py BMFR SOURCE_DIR WORK
"""
import json
import os
import shutil
import subprocess
import sys

BMFR, SOURCE, WORK = (os.path.abspath(a) for a in sys.argv[1:4])
sys.path.insert(0, os.path.join(SOURCE, "tools", "batch"))
from bmfr_batch.graph import build_tasks  # noqa: E402
from bmfr_batch.plan import PlanError, parse_plan  # noqa: E402
from bmfr_batch.tasks import digest, is_finished, write_json_atomically  # noqa: E402

GOOD = {"sequences": [{"name": "a", "scene": "cornell-moving", "width": 8, "height": 6,
                       "frames": 5, "reference_samples": 4}],
        "methods": [{"name": "bmfr"}, {"name": "svgf-q", "filter": "svgf", "preset": "quality",
                                      "set": {"taa": False}},
                    {"name": "oidn", "peer": "oidn", "set": {"quality": "fast"}}],
        "chunk_frames": 2}
failures = []


def expect_error(change, needle):
    plan = json.loads(json.dumps(GOOD))
    change(plan)
    try:
        parse_plan(json.dumps(plan), WORK, "plan.json")
    except PlanError as e:
        if needle not in str(e):
            failures.append(f"error '{e}' does not say '{needle}'")
        return
    failures.append(f"no error for a plan that should say '{needle}'")


expect_error(lambda p: p["sequences"][0].pop("width"), "sequences[0]: 'width' is required")
expect_error(lambda p: p["sequences"][0].update(widht=3), "unknown key 'widht'")
expect_error(lambda p: p["sequences"][0].update(frames=0), "'frames' = 0 must be an integer")
expect_error(lambda p: p["sequences"][0].update(samples=4), "1 sample per pixel")
expect_error(lambda p: p["sequences"][0].update(name="../x"), "'name' = \"../x\"")
expect_error(lambda p: p["sequences"].append(dict(p["sequences"][0])), "used twice")
expect_error(lambda p: p["sequences"][0].update(scene="missing.json"), "does not exist")
expect_error(lambda p: p["methods"].append({"name": "x", "filter": "nlm"}), "'filter' = \"nlm\"")
expect_error(lambda p: p["methods"].append({"name": "noisy"}), "'noisy' is the input's")
expect_error(lambda p: p["methods"].append({"name": "x", "backend": "opencl"}),
             "'backend' = \"opencl\" must be cpu, reference or cuda")
expect_error(lambda p: p.update(metrics=["psnr"]), "'metrics' = [\"psnr\"]")
expect_error(lambda p: p.update(methods=[]), "'methods' must be a list of at least one")
try:
    parse_plan("{", WORK, "plan.json")
    failures.append("no error for text that is not JSON")
except PlanError as e:
    if "plan.json: not JSON" not in str(e):
        failures.append(f"JSON error says: {e}")

# The task graph: three parts of five frames, their assembly, each method after it, one score
# after every method; a changed method changes its key and its score's, not the renders'.
plan = parse_plan(json.dumps(GOOD), WORK)
tasks = build_tasks(plan, BMFR, os.path.join(WORK, "out"))
ids = [t["id"] for t in tasks]
renders = ["render/a/0000-0002", "render/a/0002-0004", "render/a/0004-0005"]
if ids != renders + ["assemble/a", "denoise/a/bmfr", "denoise/a/svgf-q", "denoise/a/oidn",
                     "score/a"]:
    failures.append(f"tasks: {ids}")
by_id = {t["id"]: t for t in tasks}
if by_id["assemble/a"]["deps"] != renders or \
        by_id["assemble/a"]["argv"][by_id["assemble/a"]["argv"].index("--frame-range") + 1] != "0:5":
    failures.append("the assembly is not the whole range after every part")
if by_id["denoise/a/svgf-q"]["deps"] != ["assemble/a"]:
    failures.append("a denoise does not wait for the assembly")
if by_id["score/a"]["deps"] != ["denoise/a/bmfr", "denoise/a/svgf-q", "denoise/a/oidn"]:
    failures.append("the score does not wait for every method")
svgf = by_id["denoise/a/svgf-q"]["argv"]
if svgf[1:3] != ["denoise", os.path.join(WORK, "out", "sequences", "a")] or \
        "--preset" not in svgf or "taa=false" not in svgf:
    failures.append(f"svgf's command: {svgf}")
if "--quality" not in by_id["denoise/a/oidn"]["argv"]:
    failures.append("a peer's setting is not its own option")
part = by_id["render/a/0002-0004"]["argv"]
if part[part.index("--frame-range") + 1] != "2:4":
    failures.append(f"a part renders other frames: {part}")
if "--yes" not in part:
    failures.append("an estimate of over an hour would stop a part")
if "--seed" in part or "--bounces" in part:
    failures.append("a plan without seed or bounces overrides the scene's")
gpu = json.loads(json.dumps(GOOD))
gpu["methods"][0]["backend"] = "cuda"
cuda = {t["id"]: t for t in build_tasks(parse_plan(json.dumps(gpu), WORK), BMFR, WORK)}
if cuda["denoise/a/bmfr"].get("gpus") != 1 or "cuda" not in cuda["denoise/a/bmfr"]["argv"] or \
        cuda["denoise/a/svgf-q"].get("gpus"):
    failures.append("a CUDA method does not ask Ray for a GPU (or another method does)")
# The keys leave out the threads and where OUT is: the same work elsewhere is not redone.
moved = json.loads(json.dumps(GOOD))
moved["cpus_per_task"] = 2
elsewhere = build_tasks(parse_plan(json.dumps(moved), WORK), BMFR, os.path.join(WORK, "o2"))
if [t["key"] for t in elsewhere] != [t["key"] for t in tasks]:
    failures.append("other threads or another OUT path change the tasks' keys")
changed = json.loads(json.dumps(GOOD))
changed["methods"][0]["preset"] = "quality"
again = {t["id"]: t for t in build_tasks(parse_plan(json.dumps(changed), WORK), BMFR,
                                          os.path.join(WORK, "out"))}
if again[renders[0]]["key"] != by_id[renders[0]]["key"]:
    failures.append("a changed method changed a render's key")
for tid in ("denoise/a/bmfr", "score/a"):
    if again[tid]["key"] == by_id[tid]["key"]:
        failures.append(f"a changed method left {tid}'s key as it was")

# A record counts only for its key, its input's fingerprint and outputs that exist.
shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
task = dict(by_id["denoise/a/bmfr"])
write_json_atomically(task["record"], {"key": task["key"], "input": "f1"})
os.makedirs(task["output"])
if is_finished(task, "f1"):
    failures.append("a record without its outputs counts as finished")
open(os.path.join(task["output"], "report.json"), "w").close()
if not is_finished(task, "f1") or is_finished(task, "f2"):
    failures.append("a record is not judged by its input's fingerprint")
if is_finished(dict(task, key=digest("other")), "f1"):
    failures.append("a record of another command counts")

# The command: a plan error exits 2 and names it; a folder of someone else's files exits 1
# and is left as it was.
bad = os.path.join(WORK, "bad.json")
with open(bad, "w") as f:
    json.dump({"sequences": [], "methods": [{"name": "bmfr"}]}, f)
run = subprocess.run([BMFR, "batch", bad, "-o", os.path.join(WORK, "o"), "--python",
                      sys.executable], capture_output=True, text=True)
if run.returncode != 2 or "'sequences' must be a list" not in run.stderr:
    failures.append(f"a bad plan: exit {run.returncode}, {run.stderr}")
good = os.path.join(WORK, "good.json")
with open(good, "w") as f:
    json.dump(GOOD, f)
theirs = os.path.join(WORK, "theirs")
os.makedirs(theirs)
with open(os.path.join(theirs, "notes.txt"), "w") as f:
    f.write("mine")
run = subprocess.run([BMFR, "batch", good, "-o", theirs, "--python", sys.executable],
                     capture_output=True, text=True)
if run.returncode != 1 or "holds no earlier batch" not in run.stderr or \
        os.listdir(theirs) != ["notes.txt"]:
    failures.append(f"someone else's folder: exit {run.returncode}, {run.stderr}, "
                    f"{os.listdir(theirs)}")

run = subprocess.run([BMFR, "batch", good, "-o", os.path.join(WORK, "n"), "--cluster",
                      "127.0.0.1:1", "--python", sys.executable], capture_output=True, text=True)
if run.returncode != 1 or "no Ray head node answers at 127.0.0.1:1" not in run.stderr:
    failures.append(f"an address nothing answers: exit {run.returncode}, {run.stderr}")

shutil.rmtree(WORK, ignore_errors=True)
for f in failures:
    print(f"FAIL: {f}")
print("batch plan test passed" if not failures else f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
