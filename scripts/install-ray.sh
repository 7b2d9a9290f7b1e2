#!/usr/bin/env bash
# Installs Ray (pinned, with everything it pulls in) into .venv/, for `bmfr batch`: render,
# denoise and score many sequences on a Ray cluster (docs/batch.md). Needs python3-venv
# (scripts/install-deps.sh installs it, then calls this).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv
requirements=tools/batch/requirements.txt
ray=$(sed -n 's/^ray==//p' "$requirements")
if ls -d "$venv"/lib/python3*/site-packages/ray-"$ray".dist-info > /dev/null 2>&1 &&
    [ -x "$venv/bin/pip" ]; then
    exit 0
fi
echo "installing Ray $ray from PyPI into $venv/ (for bmfr batch)"
python=python3
[ -x /usr/bin/python3 ] && python=/usr/bin/python3
[ -x "$venv/bin/pip" ] || "$python" -m venv --clear "$venv"
"$venv/bin/python" -m pip install --disable-pip-version-check -q -r "$requirements"
"$venv/bin/python" -c "import ray" > /dev/null
