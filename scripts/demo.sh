#!/usr/bin/env bash
# Quick start, first command: install, build, and run the main job on the built-in default.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/bmfr demo --output bmfr-demo "$@"
