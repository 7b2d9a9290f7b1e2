#!/usr/bin/env bash
# Configures and builds bmfr (Release) into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
# Debian's python3 (with its numpy and pytest) builds and runs the module, not a pyenv shim.
py=()
[ -x /usr/bin/python3 ] && py=(-DPython3_EXECUTABLE=/usr/bin/python3)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${py[@]}" > /dev/null
cmake --build build -j "$(nproc)"
# Which backends this build has (the cuda backend needs nvcc at configure time, no GPU).
build/bmfr --version
