#!/usr/bin/env bash
# `bmfr peer oidn` against OIDN through its own Python binding, in the .venv that
# scripts/install-oidn.sh makes (pyoidn, pinned): renders a small sequence, runs the peer with
# each --prefilter, and compares every frame (oidn_against_pyoidn.py).
# Usage: oidn_pyoidn.sh SOURCE_DIR MODULE_DIR BMFR WORK_DIR
set -euo pipefail
src=$1
module=$2
bmfr=$3
work=$4
python=$src/.venv/bin/python
if [ ! -x "$python" ] || ! "$python" -c "import pyoidn" 2> /dev/null; then
    echo "no pyoidn in $src/.venv: run scripts/install-oidn.sh (scripts/install-deps.sh does)" >&2
    exit 1
fi
rm -rf "$work"
"$bmfr" render -s room-light --width 67 --height 45 --frames 3 --reference-spp 64 -o "$work/seq" -q
for p in none fast accurate; do
    "$bmfr" peer oidn "$work/seq" -o "$work/peer/$p" --prefilter "$p" --no-flip -q
done
PYTHONPATH=$module "$python" "$src/tests/python/oidn_against_pyoidn.py" "$work/seq" "$work/peer"
