"""Wall time of one plan on a one-node Ray cluster against a two-node one, both on this machine,
and against its commands run one after another without Ray (each with every core), run
alternately from scratch (docs/results/2026-12-05-batch-ray.md).

    .venv/bin/python tools/batch/time_nodes.py PLAN BMFR WORK [ROUNDS]

The one node gets every core; the two nodes split them. On one machine both share the same
cores, so this measures the cost of the second node (scheduling, a second raylet), not a speed-up.
"""
import os
import shutil
import subprocess
import sys
import time

from bmfr_batch.graph import build_tasks
from bmfr_batch.local_cluster import LocalCluster
from bmfr_batch.plan import load_plan


def without_ray(plan_path, bmfr, out, cores):
    """The plan's commands in order in this process, each with every core: the baseline."""
    plan = load_plan(plan_path)
    plan.cpus_per_task = cores
    for task in build_tasks(plan, bmfr, out):
        subprocess.run(task["argv"], check=True, capture_output=True)


def main():
    plan, bmfr, work = (os.path.abspath(a) for a in sys.argv[1:4])
    rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 2
    cores = os.cpu_count()
    layouts = {"no Ray": [cores], "one node": [cores],
               "two nodes": [cores // 2, cores - cores // 2]}
    times = {name: [] for name in layouts}
    for r in range(rounds):
        for name, cpus in layouts.items():
            out = os.path.join(work, f"{name.replace(' ', '-')}-{r}")
            shutil.rmtree(out, ignore_errors=True)
            if name == "no Ray":
                start = time.monotonic()
                without_ray(plan, bmfr, out, cores)
                times[name].append(time.monotonic() - start)
                print(f"round {r + 1}, {name} ({cores} threads a command): "
                      f"{times[name][-1]:.1f} s", flush=True)
                continue
            with LocalCluster(cpus, os.path.join(work, "logs")) as cluster:
                start = time.monotonic()
                run = subprocess.run([bmfr, "batch", plan, "-o", out, "--cluster",
                                      cluster.address, "-q", "--python", sys.executable],
                                     env=cluster.env, capture_output=True, text=True)
                seconds = time.monotonic() - start
            if run.returncode != 0:
                sys.exit(f"{name}: bmfr batch exited {run.returncode}:\n{run.stderr}")
            times[name].append(seconds)
            print(f"round {r + 1}, {name} ({'+'.join(map(str, cpus))} CPUs): {seconds:.1f} s",
                  flush=True)
    for name, t in times.items():
        print(f"{name}: median {sorted(t)[len(t) // 2]:.1f} s over {len(t)} runs")


if __name__ == "__main__":
    main()
