#!/usr/bin/env bash
# The CUDA backend's checks on a machine with an NVIDIA GPU, in one go.
#
#   bash scripts/gpu-check.sh prepare   # here (Debian, nvcc, no GPU needed): build, then pack
#                                       # bmfr, bmfr_tests and the libraries they load into
#                                       # gpu-carry/bundle.tar.xz (git-ignored)
#   bash scripts/gpu-check.sh run [STEP ...]  # on the GPU machine, with gpu-carry/ carried
#                                       # along: writes its logs to $OUT (or gpu-check-out/);
#                                       # STEPs (tests demo bench bench-quality bench-device
#                                       # bench-filters sanitizer ncu) pick some, default all
#
# The GPU machine has nvcc, CMake and Python but none of our Debian packages and no network, so
# the binaries travel with their libraries (Embree, TBB, OpenEXR, fmt, libstdc++ ...), and with
# this machine's glibc and loader in case that machine's glibc is older than 2.36. What `run`
# does, each step time-limited:
#   1. the conformance suite for cuda (all four filters), device buffers on either stream, two
#      filters of different block sizes alternating, the caller's device kept, and the
#      team-fit and Householder tests;
#   2. cornell-moving rendered with Mara's factored paths, then BMFR (both presets), SVGF, WALR
#      and Mara 2017 on cuda and on the CPU backend, each scored against the reference by
#      `bmfr denoise`;
#   3. `bmfr bench --backend cuda` at 720p, 1080p and 4K beside the CPU backend, the quality
#      preset beside the faithful one, again with the input in device memory (JSON), and every
#      filter beside BMFR and the memory floor with device buffers at 720p, 1080p and 4K;
#   4. compute-sanitizer memcheck and racecheck on a small sequence, every filter, where it
#      works.
# The step limits add up to about eight minutes, one device call: run it once with
# timeout_s=540, read summary.txt, rerun only what failed.
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

export PATH="$PATH:/usr/local/cuda/bin"
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
shift || true
steps=" $* " # run [STEP ...]: only those (tests demo bench bench-quality bench-device ...)
step() { # step NAME SECONDS COMMAND... : runs it, logs to $out/NAME.log, notes its exit status
    local name=$1 limit=$2
    shift 2
    [ "$steps" = "  " ] || [[ "$steps" == *" $name "* ]] || return 0
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
    --gtest_filter='AllBackendsAndFilters/Conformance.*/cuda_*:CudaDeviceBuffers.*:CudaFilters.*:TeamFit.*:Householder.*'

demo=$work/demo
step demo 100 bash -c "
    set -e
    '$bmfr' render -o '$demo/input' -s cornell-moving --width 320 --height 240 --frames 16 \
        --reference-spp 64 --paths mara --quiet
    for run in 'bmfr cpu faithful' 'bmfr cuda faithful' 'bmfr cpu quality' 'bmfr cuda quality' \
               'svgf cpu faithful' 'svgf cuda faithful' 'walr cpu quality' 'walr cuda quality' \
               'mara2017 cpu quality' 'mara2017 cuda quality'; do
        set -- \$run
        echo \"== \$1 on \$2, \$3 preset\"
        '$bmfr' denoise '$demo/input' -o \"$demo/\$1-\$2-\$3\" --filter \$1 --backend \$2 \
            --preset \$3 --no-png --overwrite | grep -E 'RMSE|^  (noisy|bmfr|svgf|walr|mara2017) '
    done"

step bench 60 "$bmfr" bench --backend cuda --baseline-backend cpu \
    --sizes 1280x720,1920x1080,3840x2160
step bench-quality 40 "$bmfr" bench --backend cuda --preset quality --baseline-backend cuda \
    --sizes 1280x720,1920x1080
step bench-device 40 bash -c "
    for p in faithful quality; do
        '$bmfr' bench --backend cuda --device-buffers --no-baseline --preset \$p -q \
            --sizes 1280x720,1920x1080,3840x2160 --json
    done"
step bench-filters 60 "$bmfr" bench --backend cuda --filters all --device-buffers \
    --sizes 1280x720,1920x1080,3840x2160

if command -v compute-sanitizer > /dev/null; then
    small=$work/small
    "$bmfr" synth -o "$small" --width 77 --height 45 --frames 3 --quiet
    step sanitizer 90 bash -c "
        for tool in memcheck racecheck; do
            for f in bmfr svgf walr mara2017 quality; do
                args=\"--filter \$f\"
                [ \$f = quality ] && args='--filter bmfr --preset quality'
                compute-sanitizer --tool \$tool --error-exitcode 9 \
                    '$bmfr' denoise '$small' -o \"$work/san-\$f\" \$args --backend cuda -q --overwrite \
                    || echo \"\$tool on \$f: FAILED (\$?)\"
            done
        done"
else
    say "== sanitizer: compute-sanitizer not found"
fi
# The fit kernel's counters at 720p, both presets (where ncu can read them).
if command -v ncu > /dev/null; then
    step ncu 40 bash -c "
        for p in faithful quality; do
            ncu --clock-control none --kernel-name regex:fitKernel --launch-skip 6 \
                --launch-count 1 --section SpeedOfLight --section Occupancy \
                --section LaunchStats --section MemoryWorkloadAnalysis \
                '$bmfr' bench --backend cuda --no-baseline --preset \$p --sizes 1280x720 \
                --warmup 2 --frames 8 -q
        done"
else
    say "== ncu: not found"
fi
# The device tool brings back 8 files at most: the logs travel as one archive.
if [ "$(ls "$out" | wc -l)" -gt 8 ]; then
    (cd "$out" && tar -czf logs.tgz ./*.log && rm ./*.log)
fi
say "== done"
