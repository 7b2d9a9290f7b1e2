"""Runs a script in Blender for the Blender tools and tests: Debian's `blender` (or $BLENDER) in the
background with factory settings, or, with $BLENDER_PYTHON, a Python that has PyPI's bpy module
(tests/blender/with_bpy.sh makes one). Scripts take their arguments after "--" and open any .blend
themselves, so they run the same in both."""
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def blender_command():
    """The command prefix that runs a script, or None when there is no Blender."""
    if os.environ.get("BLENDER_PYTHON"):
        return [os.environ["BLENDER_PYTHON"]]
    blender = os.environ.get("BLENDER") or shutil.which("blender")
    return [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python"] if blender else None


def require_blender():
    """Exits 77 (ctest's skip) with a message when there is no Blender."""
    if not blender_command():
        print("blender is not installed: skipped")
        sys.exit(77)


def run(*cmd, env=None, expect_failure=False):
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True,
                       env=dict(os.environ, **(env or {})))
    if (r.returncode != 0) != expect_failure:
        sys.exit(f"{'succeeded' if r.returncode == 0 else f'failed ({r.returncode})'}: "
                 f"{' '.join(map(str, cmd))}\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    return r.stdout


def run_script(script, *args, env=None, expect_failure=False):
    return run(*blender_command(), script, "--", *args, env=env, expect_failure=expect_failure)


def make_scene(blend, frames, size):
    run_script(os.path.join(ROOT, "tools/blender/make_test_scene.py"), blend, "--frames", frames,
               "--size", size)


def render(blend, seq, *options):
    return run_script(os.path.join(ROOT, "tools/blender/render_sequence.py"), seq, "--blend",
                      blend, "-q", *options)


def info():
    """(version, whether its Cycles has its own denoiser): PyPI's bpy has OIDN, Debian's 3.4
    not."""
    words = run_script(os.path.join(ROOT, "tools/blender/print_version.py")).split()
    at = words.index("version")
    return words[at + 1], words[words.index("oidn", at) + 1] == "True"
