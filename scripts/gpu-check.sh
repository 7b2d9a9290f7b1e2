#!/usr/bin/env bash
# The CUDA backend's checks on a machine with an NVIDIA GPU, in one go.
#
#   bash scripts/gpu-check.sh prepare   # here (Debian, nvcc, no GPU needed): build, then pack
#                                       # bmfr, bmfr_tests and the libraries they load into
#                                       # gpu-carry/bundle.tar.xz (git-ignored)
#   bash scripts/gpu-check.sh run       # on the GPU machine, with gpu-carry/ carried along:
#                                       # writes its logs to $OUT (or gpu-check-out/)
#
# The GPU machine has nvcc, CMake and Python but none of our Debian packages and no network, so
# the binaries travel with their libraries (Embree, TBB, OpenEXR, fmt, libstdc++ ...), and with
# this machine's glibc and loader in case that machine's glibc is older than 2.36. What `run`
# does, each step time-limited:
#   1. the conformance suite for cuda (bmfr, svgf), device buffers on either stream, and the
#      team-fit and Householder tests;
#   2. the demo: BMFR and SVGF on cuda against the CPU backend, scored by `bmfr eval`;
#   3. `bmfr bench --backend cuda` at 720p, 1080p and 4K beside the CPU backend, again with the
#      input in device memory (JSON), and SVGF at 720p;
#   4. compute-sanitizer memcheck and racecheck on a small sequence, where it works.
# The step limits add up to under ten minutes, one device call: run it once with
# timeout_s=600, read summary.txt, rerun only what failed.
set -uo pipefail
cd "$(dirname "$0")/.."
mode=${1:-run}

if [ "$mode" = prepare ]; then
    set -e
    bash scripts/build.sh
    rm -rf gpu-carry && mkdir -p gpu-carry/stage/lib gpu-carry/stage/glibc
    cp build/bmfr build/tests/bmfr_tests gpu-carry/stage/
    libs=$(ldd build/bmfr build/tests/bmfr_tests | awk '/=> \// {print $3}' | sort -u)
    echo "$libs" | grep -Ev '/(libc|libm|libdl|librt|libpthread)\.so' |
        xargs -I{} cp -L {} gpu-carry/stage/lib/
    # This machine's glibc and loader, used there only if its own glibc is too old.
    echo "$libs" | grep -E '/(libc|libm|libdl|librt|libpthread)\.so' |
        xargs -I{} cp -L {} gpu-carry/stage/glibc/
    cp -L /lib64/ld-linux-x86-64.so.2 gpu-carry/stage/glibc/
    tar -C gpu-carry/stage -cJf gpu-carry/bundle.tar.xz .
    rm -rf gpu-carry/stage
    ls -la gpu-carry/bundle.tar.xz
    echo "carry gpu-carry; run: bash scripts/gpu-check.sh run"
    exit 0
fi

out=${OUT:-gpu-check-out}
mkdir -p "$out"
work=/tmp/bmfr-gpu
rm -rf "$work" && mkdir -p "$work"
tar -C "$work" -xJf gpu-carry/bundle.tar.xz || { echo "no gpu-carry/bundle.tar.xz: run prepare first"; exit 1; }
export LD_LIBRARY_PATH="$work/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# The binaries through the machine's own loader, or through ours if its glibc is too old.
mkdir -p "$work/bin"
for b in bmfr bmfr_tests; do
    printf '#!/bin/sh\nexec "%s" "$@"\n' "$work/$b" > "$work/bin/$b"
    chmod +x "$work/bin/$b"
done
if ! "$work/bin/bmfr" --version > /dev/null 2>&1; then
    for b in bmfr bmfr_tests; do
        printf '#!/bin/sh\nexec "%s" --library-path "%s" "%s" "$@"\n' \
            "$work/glibc/ld-linux-x86-64.so.2" "$work/glibc:$LD_LIBRARY_PATH" "$work/$b" \
            > "$work/bin/$b"
    done
fi
bmfr=$work/bin/bmfr
summary=$out/summary.txt
say() { echo "$*" | tee -a "$summary"; }
step() { # step NAME SECONDS COMMAND... : runs it, logs to $out/NAME.log, notes its exit status
    local name=$1 limit=$2
    shift 2
    local t0=$SECONDS
    timeout "$limit" "$@" > "$out/$name.log" 2>&1
    local rc=$?
    say "== $name: exit $rc in $((SECONDS - t0)) s"
    tail -n 25 "$out/$name.log" | tee -a "$summary"
}

say "== machine"
nvidia-smi -L 2>&1 | tee -a "$summary"
"$bmfr" --version 2>&1 | tee -a "$summary"

step tests 140 "$work/bin/bmfr_tests" \
    --gtest_filter='AllBackendsAndFilters/Conformance.*/cuda_bmfr:AllBackendsAndFilters/Conformance.*/cuda_svgf:CudaDeviceBuffers.*:TeamFit.*:Householder.*'

demo=$work/demo
step demo 120 bash -c "
    set -e
    '$bmfr' demo -o '$demo' --quiet
    for f in bmfr svgf; do
        '$bmfr' denoise '$demo/input' -o '$demo/cpu-\$f' --filter \$f --backend cpu -q
        '$bmfr' denoise '$demo/input' -o '$demo/cuda-\$f' --filter \$f --backend cuda -q
    done
    '$bmfr' eval -r '$demo/input' -m noisy cpu-bmfr='$demo/cpu-bmfr' cuda-bmfr='$demo/cuda-bmfr' \
        cpu-svgf='$demo/cpu-svgf' cuda-svgf='$demo/cuda-svgf' -o '$demo/eval'"

step bench 140 "$bmfr" bench --backend cuda --baseline-backend cpu \
    --sizes 1280x720,1920x1080,3840x2160
step bench-device 50 "$bmfr" bench --backend cuda --device-buffers --no-baseline \
    --sizes 1280x720,1920x1080,3840x2160 --json
step bench-svgf 50 "$bmfr" bench --backend cuda --filter svgf --baseline-backend cpu \
    --sizes 1280x720

if command -v compute-sanitizer > /dev/null; then
    small=$work/small
    "$bmfr" synth -o "$small" --width 77 --height 45 --frames 3 --quiet
    step sanitizer 90 bash -c "
        for tool in memcheck racecheck; do
            for f in bmfr svgf; do
                compute-sanitizer --tool \$tool --error-exitcode 9 \
                    '$bmfr' denoise '$small' -o '$work/san-\$f' --filter \$f --backend cuda -q \
                    || echo \"\$tool on \$f: FAILED (\$?)\"
            done
        done"
else
    say "== sanitizer: compute-sanitizer not found"
fi
say "== done"
