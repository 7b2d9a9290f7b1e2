#!/usr/bin/env bash
# bmfr's FLIP against NVIDIA's (PyPI flip-evaluator, pinned) in a virtual environment of its
# own: Debian's Python refuses system-wide pip installs.
# Usage: flip_nvidia.sh SOURCE_DIR MODULE_DIR WORK_DIR [PYTHON]
set -euo pipefail
src=$1
module=$2
work=$3
python=${4:-python3}
if [ ! -x "$work/venv/bin/python" ]; then
    rm -rf "$work"
    "$python" -m venv "$work/venv"
    "$work/venv/bin/pip" --disable-pip-version-check -q install numpy==2.2.6 flip-evaluator==1.7
fi
PYTHONPATH=$module "$work/venv/bin/python" "$src/tests/python/flip_against_nvidia.py"
