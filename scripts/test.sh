#!/usr/bin/env bash
# Quick start, second command: install, build, and run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --tests
bash scripts/build.sh
cd build
# Every test carries a label (tests/CMakeLists.txt), so a label selects every suite it names.
unlabelled=$(ctest -N -LE '^(unit|conformance|integration|quality|external)$' | tail -1)
[ "$unlabelled" = "Total Tests: 0" ] || { echo "tests without a label: $unlabelled" >&2; exit 1; }
ctest --output-on-failure -j "$(nproc)"
