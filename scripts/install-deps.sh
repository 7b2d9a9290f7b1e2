#!/usr/bin/env bash
# Installs the Debian packages bmfr needs to build and test. Skips apt when all are present.
#   install-deps.sh [--tests]   --tests adds what only the tests need: Blender (the Cycles round
#                               trip), chromium and chromium-driver (the report in a browser),
#                               ffmpeg (eval --video) and python3-venv (the Python package in a
#                               fresh venv); the library and the demo never need them.
set -euo pipefail
pkgs=(cmake g++ make pkg-config libopenexr-dev libimath-dev libtbb-dev libeigen3-dev libcli11-dev
      nlohmann-json3-dev libfmt-dev libstb-dev libgtest-dev libbenchmark-dev libembree-dev
      libtinygltf-dev libtinyobjloader-dev python3 python3-skimage clang libclang-rt-14-dev
      python3-dev python3-numpy python3-pytest pybind11-dev python3-pil)
if [ "${1:-}" = --tests ]; then
    pkgs+=(blender chromium chromium-driver ffmpeg python3-venv)
fi
missing=()
for p in "${pkgs[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    echo "installing: ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
