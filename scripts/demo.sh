#!/usr/bin/env bash
# Quick start, first command: install what `bmfr` needs, build only it, and run the demo on the
# built-in scene (render, denoise with the four filters, their presets and OIDN, score, report).
# Arguments go to `bmfr demo`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --demo
bash scripts/build.sh --demo
./build/bmfr demo --output bmfr-demo "$@"
