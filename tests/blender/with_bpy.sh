#!/usr/bin/env bash
# The Blender tests with a current Blender: PyPI's bpy module (4.2, which has Cycles' own OIDN)
# in a virtual environment under BUILD/bpy-venv, in place of Debian's blender 3.4.
#   tests/blender/with_bpy.sh BUILD [TEST ...]      (default: every Blender test)
set -euo pipefail
build=$(cd "$1" && pwd)
shift
here=$(cd "$(dirname "$0")" && pwd)
tests=("$@")
[ ${#tests[@]} -gt 0 ] || tests=(round_trip trail_test addon_test visibility_test)
venv=$build/bpy-venv
if [ ! -x "$venv/bin/python" ]; then
    /usr/bin/python3 -m venv "$venv"
    "$venv/bin/pip" install --disable-pip-version-check -q bpy==4.2.0 numpy==1.26.4
fi
for t in "${tests[@]}"; do
    echo "== $t with bpy $("$venv/bin/pip" show bpy | sed -n 's/^Version: //p')"
    BLENDER_PYTHON=$venv/bin/python PYTHONPATH=$build/python BMFR_CLI=$build/bmfr \
        /usr/bin/python3 "$here/$t.py"
done
