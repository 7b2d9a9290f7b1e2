#!/usr/bin/env bash
# Configures and builds bmfr (Release) into build/.
#   build.sh          everything: the library, the CLI, the tests, the Python module and, when
#                     nvcc is found, the CUDA backend (no GPU is needed to build it)
#   build.sh --demo   only the `bmfr` command, without the CUDA backend (what the demo runs)
set -euo pipefail
cd "$(dirname "$0")/.."
# With ccache (scripts/install-deps.sh installs it for the tests), compiles go through it, paths
# under the source tree taken relative: the Python package test's wheel build
# (tests/python/package_test.sh, given this launcher) then reuses this build's library objects.
# Depend mode takes the headers from the compiler's -MD output instead of running the
# preprocessor once more per file (0.3 s to 0.4 s of a fresh build's every file).
launcher=-DCMAKE_CXX_COMPILER_LAUNCHER=
if command -v ccache > /dev/null; then
    launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=env;CCACHE_BASEDIR=$PWD;CCACHE_DEPEND=1;ccache"
fi
if [ "${1:-}" = --demo ]; then
    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBMFR_BUILD_TESTS=OFF -DBMFR_CUDA=OFF \
          -DBMFR_PYTHON=OFF "$launcher" > /dev/null
    cmake --build build -j "$(nproc)" --target bmfr
else
    # Debian's python3 (with its numpy and pytest) builds and runs the module, not a pyenv shim.
    py=()
    [ -x /usr/bin/python3 ] && py=(-DPython3_EXECUTABLE=/usr/bin/python3)
    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBMFR_BUILD_TESTS=ON -DBMFR_CUDA=AUTO \
          -DBMFR_PYTHON=AUTO "${py[@]}" "$launcher" > /dev/null
    cmake --build build -j "$(nproc)"
fi
# Which backends this build has.
build/bmfr --version
