#!/usr/bin/env bash
# The package as a user installs it: a fresh virtual environment, the wheel built by `pip wheel`
# from the source tree (scikit-build-core, pybind11 from PyPI), installed with pinned numpy and
# pytest, and the pytest suite run against that install from outside the source tree.
# Usage: package_test.sh SOURCE_DIR WORK_DIR BMFR_CLI [PYTHON [LAUNCHER...]]
set -euo pipefail
src=$1
work=$2
cli=$3
python=${4:-python3}
launcher=("${@:5}") # the build's CMAKE_CXX_COMPILER_LAUNCHER, a word each
rm -rf "$work"
mkdir -p "$work"
"$python" -m venv "$work/venv"
pip=("$work/venv/bin/pip" --disable-pip-version-check -q)
"${pip[@]}" install numpy==2.2.6 pytest==8.3.5
# With the build's launcher (scripts/build.sh's ccache), the wheel's CMake tree sits beside
# build/ and CXX names the build's compiler (scikit-build-core would take Python's), so that,
# paths under the source tree taken relative, its library compiles are the build's and come from
# the cache. The tree is made afresh and removed afterwards.
config=()
if [ ${#launcher[@]} -gt 0 ]; then
    tree="$src/build-wheel-$$" # one per run: two build trees may test from one source tree
    trap 'rm -rf "$tree"' EXIT
    export CCACHE_STATSLOG=$work/ccache.log
    list=$(IFS=';'; echo "${launcher[*]}") # a CMake list again
    config=(--config-settings=build-dir="$tree"
            --config-settings=cmake.define.CMAKE_CXX_COMPILER_LAUNCHER="$list")
fi
start=$(date +%s)
CMAKE_BUILD_PARALLEL_LEVEL=$(nproc) "${pip[@]}" wheel --no-deps "${config[@]}" -w "$work/wheels" \
    "$src"
"${pip[@]}" install "$work"/wheels/bmfr-*.whl
echo "wheel built and installed in $(($(date +%s) - start)) s: $(basename "$work"/wheels/bmfr-*.whl)"
if [ -f "$work/ccache.log" ]; then
    echo "compiles from the cache: $(grep -c '_cache_hit$' "$work/ccache.log" || true)" \
         "of $(grep -c '^# ' "$work/ccache.log" || true)"
fi
cd "$work"
"$work/venv/bin/python" -c "import bmfr, os; print('bmfr', bmfr.__version__, 'from', os.path.dirname(bmfr.__file__))"
BMFR_CLI=$cli "$work/venv/bin/python" -m pytest -q -p no:cacheprovider "$src/tests/python"
echo "python package test passed"
