#!/usr/bin/env bash
# decisions_without_fma.sh NVCC SOURCE_DIR WORK_DIR FLAGS...: compiles decisions_probe.cu to PTX
# with the library's CUDA rounding FLAGS (none must contract a multiply and an add) and with
# --fmad=true (some must, or the probe tells nothing).
set -euo pipefail
nvcc=$1 src=$2 work=$3
shift 3
probe() { # probe OUT FLAGS...: the probe's PTX, and how many fused multiply-adds it holds
    local out=$1
    shift
    "$nvcc" -ptx -arch=compute_90 -std=c++20 -O3 "$@" -I"$src/src" -I"$src/include" \
        "$src/tests/cuda/decisions_probe.cu" -o "$out"
    grep -c 'fma\.rn\.f32' "$out" || true
}
with=$(probe "$work/decisions_probe_fmad.ptx" --fmad=true)
without=$(probe "$work/decisions_probe.ptx" "$@")
echo "fused multiply-adds in the decisions: $without with the library's flags ($*), $with with --fmad=true"
[ "$with" -gt 0 ] || { echo "the probe holds none even with --fmad=true: it tests nothing"; exit 1; }
[ "$without" -eq 0 ] || { echo "the library's flags let nvcc fuse them (see $work/decisions_probe.ptx)"; exit 1; }
echo "no fused multiply-add in the decisions"
