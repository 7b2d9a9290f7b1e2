#!/usr/bin/env bash
# Installs the Debian packages bmfr needs (skipping apt when all are present), then Intel Open
# Image Denoise from PyPI into .venv/ (scripts/install-oidn.sh), the peer the demo compares with,
# and with --tests Ray (scripts/install-ray.sh), which `bmfr batch` runs on.
#   install-deps.sh --demo    only what `bmfr` itself needs to build (the demo's command)
#   install-deps.sh           also the libraries and tools the tests, sanitizers and the Python
#                             module build with (GoogleTest, Google Benchmark, clang, pybind11...)
#   install-deps.sh --tests   also what only the tests run: Blender (the Cycles round trip),
#                             chromium and chromium-driver (the report in a browser), ffmpeg
#                             (eval --video)
set -euo pipefail
case "${1:-}" in
"" | --demo | --tests) ;;
*)
    echo "install-deps.sh: unknown option '$1' (use --demo, --tests or nothing)" >&2
    exit 2
    ;;
esac
pkgs=(cmake g++ make pkg-config libopenexr-dev libimath-dev libtbb-dev libcli11-dev
      nlohmann-json3-dev libfmt-dev libstb-dev libembree-dev libtinygltf-dev libtinyobjloader-dev
      python3-venv)
if [ "${1:-}" != --demo ]; then
    pkgs+=(libeigen3-dev libgtest-dev libbenchmark-dev python3 python3-skimage clang
           libclang-rt-14-dev python3-dev python3-numpy python3-pytest pybind11-dev python3-pil
           ccache)
fi
if [ "${1:-}" = --tests ]; then
    pkgs+=(blender chromium chromium-driver ffmpeg)
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
# Without PyPI the rest still builds and the demo runs without OIDN (it says so); the tests that
# run OIDN fail and say how to install it.
bash "$(dirname "$0")/install-oidn.sh" ||
    echo "install-deps.sh: warning: Intel Open Image Denoise was not installed (see above)" >&2
# Ray, for `bmfr batch` and its cluster test: with the tests, or on its own by install-ray.sh.
if [ "${1:-}" = --tests ]; then
    bash "$(dirname "$0")/install-ray.sh" ||
        echo "install-deps.sh: warning: Ray was not installed (see above)" >&2
fi
