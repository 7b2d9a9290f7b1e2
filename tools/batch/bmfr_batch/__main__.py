"""python -m bmfr_batch PLAN -o OUT --bmfr PATH: what `bmfr batch` runs (docs/batch.md)."""
import argparse
import os
import sys

from .driver import BatchError, run_batch
from .plan import PlanError, load_plan


def main(argv=None):
    p = argparse.ArgumentParser(
        prog="bmfr batch",
        description="render, denoise and score the sequences of a plan on a Ray cluster")
    p.add_argument("plan", help="the plan (JSON: sequences, methods, metrics; docs/batch.md)")
    p.add_argument("-o", "--output", required=True,
                   help="output folder: new, empty, or an earlier batch's (then it resumes)")
    p.add_argument("--cluster", default="auto",
                   help="auto (join the Ray cluster of RAY_ADDRESS or this machine's, else start "
                        "one here), local (start one here) or ADDRESS (host:port of a head "
                        "node); default auto")
    p.add_argument("--retries", type=int, default=3,
                   help="attempts after the first of a task whose worker or bmfr was killed, "
                        "0-100; default 3")
    p.add_argument("--bmfr", required=True, help="the bmfr executable (the same path on "
                   "every node)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress or summary")
    args = p.parse_args(argv)
    if not 0 <= args.retries <= 100:
        p.error(f"--retries {args.retries} is outside [0, 100]")
    try:
        plan = load_plan(args.plan)
        rows, summary = run_batch(plan, args.output, os.path.abspath(args.bmfr), args.cluster,
                                  args.retries, args.quiet)
    except PlanError as e:
        print(f"bmfr: {e}", file=sys.stderr)
        return 2
    except BatchError as e:
        print(f"bmfr: {e}", file=sys.stderr)
        return 1
    except ImportError as e:
        print(f"bmfr: Ray is not installed for {sys.executable} ({e}); run "
              "scripts/install-ray.sh", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("bmfr: interrupted; run the same command to resume", file=sys.stderr)
        return 130
    except OSError as e:  # the output folder unwritable, a plan file unreadable
        print(f"bmfr: {e.filename or ''}: {e.strerror or e}", file=sys.stderr)
        return 1
    for failure in summary["failed"]:
        print(f"bmfr: failed: {failure}", file=sys.stderr)
    if not args.quiet:
        nodes = (f"{len(summary['nodes'])}: " + ", ".join(summary["nodes"]) if summary["nodes"]
                 else "none (all finished earlier)")
        print(f"{summary['run']} task(s) run, {summary['skipped']} finished earlier, "
              f"{len(summary['failed'])} failed, {summary['retried']} retried, in "
              f"{summary['seconds']:.1f} s; nodes: {nodes}")
        print(f"{len(rows)} rows: {os.path.join(args.output, 'results.csv')}, results.json, "
              "index.html")
    return 1 if summary["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
