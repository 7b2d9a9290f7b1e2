#!/usr/bin/env bash
# Builds the tests and the CLI with AddressSanitizer and UndefinedBehaviorSanitizer into
# build-asan/ and runs the tests labelled unit, conformance and integration (tests/CMakeLists.txt;
# LABELS, a ctest label regex, overrides them: "." runs every label).
#   sanitize.sh [LABELS]
set -euo pipefail
cd "$(dirname "$0")/.."
labels=${1:-'^(unit|conformance|integration)$'}
# BMFR_SIMD_SINGLE_PATH: the CPU passes on one instruction set, the baseline (src/backend/cpu/
# simd.h): the others are the same source, so they index memory alike, and compiling three
# copies of each pass under the sanitizers costs more than any other part of the build.
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
flags="$flags -DBMFR_SIMD_SINGLE_PATH=1"
# -O1: the sanitizers need no more, and it halves the build on two cores; the tests' and the
# command's own code, which run no hot loop, -O0 (half again).
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_C_FLAGS="$flags" \
    -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DBMFR_TESTS_OPTIMIZATION=-O0 \
    -DBMFR_CLI_OPTIMIZATION=-O0 \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DBMFR_PYTHON=OFF \
    -DBMFR_CUDA=OFF > /dev/null
cmake --build build-asan -j "$(nproc)" \
    --target bmfr bmfr_tests bmfr_allocation_test bmfr_minimal_example bmfr_c_api_program \
    bmfr_denoise_frame > /dev/null
cd build-asan
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --output-on-failure -j "$(nproc)" -L "$labels"
