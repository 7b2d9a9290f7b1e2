#!/usr/bin/env bash
# Builds the tests and the CLI with AddressSanitizer and UndefinedBehaviorSanitizer into
# build-asan/ and runs the suites that cover the readers, the writers, every filter on every
# backend and the command line (FILTER overrides the ctest regex; "." runs everything).
set -euo pipefail
cd "$(dirname "$0")/.."
filter=${1:-'Hardening|SequenceIo|EndToEnd|Conformance|Svgf|Walr\.|Accumulation|Reprojection|MotionVectors\.|RenderMotion\.|Cli|Householder|Multilayer|Report|FlipReference|Metrics\.'}
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# -O1: the sanitizers need no more, and it halves the build on two cores.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DBMFR_PYTHON=OFF \
    -DBMFR_CUDA=OFF > /dev/null
cmake --build build-asan -j "$(nproc)" --target bmfr bmfr_tests > /dev/null
cd build-asan
# The CPU backend's conformance cases run on the baseline path alone here: the AVX2 and AVX-512
# paths are the same source touching the same addresses, and the normal run covers them.
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --output-on-failure -j "$(nproc)" -R "$filter" -E "Conformance\\..*/cpu_(avx2|avx512)_"
