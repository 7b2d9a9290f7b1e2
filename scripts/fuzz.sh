#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang, ASan + UBSan) and runs each for SECONDS seconds
# (default 60) on seed corpora made by `bmfr synth` plus the committed regression inputs in
# tests/fuzz/corpus/. A crash, a leak, a timeout or an allocation over 1 GiB is a finding: the
# run stops, exits 1 and leaves the input in build-fuzz/findings/. Needs build/bmfr (for the
# seeds). FUZZ_SEED fixes libFuzzer's seed (CI uses 1, so its run is a prefix of one checked
# here; 0 = random). Usage: bash scripts/fuzz.sh [SECONDS] [HARNESS ...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(exr camera_header layouts scene cli_parsers)

cmake -S tests/fuzz -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    > /dev/null
cmake --build build-fuzz -j "$(nproc)" > /dev/null

# Seed corpora from bmfr synth, in both layouts, and the repro files.
seeds=build-fuzz/seeds
if [ ! -d "$seeds" ]; then
    ./build/bmfr synth -o "$seeds/manifest" --width 16 --height 8 --frames 2 -q
    ./build/bmfr synth -o "$seeds/bmfr" --width 16 --height 8 --frames 2 --layout bmfr -q
fi
corpus=build-fuzz/corpus
rm -rf "$corpus"
for h in exr camera_header layouts scene cli_parsers; do mkdir -p "$corpus/$h"; done
cp "$seeds"/manifest/color_0000.exr "$seeds"/manifest/material_id_0000.exr "$corpus/exr/"
cp "$seeds"/bmfr/camera_matrices.h "$corpus/camera_header/"
{ printf '\001'; cat "$seeds/manifest/sequence.json"; } > "$corpus/layouts/manifest"
{ printf '\000'; cat "$seeds/bmfr/camera_matrices.h"; } > "$corpus/layouts/bmfr"
printf '%s' '{"mesh": "builtin:cornell", "width": 16, "height": 8, "frames": 2,
  "sun": {"direction": [0.3, 1, 0.1], "irradiance": [5, 5, 5]},
  "lights": [{"type": "quad", "centre": [0, 1.9, 0], "u": [0.5, 0, 0], "v": [0, 0, 0.5],
              "radiance": [20, 18, 15], "path": [{"frame": 0, "centre": [0, 1.9, 0]}]}],
  "camera": {"keyframes": [{"frame": 0, "position": [0, 1, 3.4], "target": [0, 1, 0],
                            "fov_deg": 40}]}}' > "$corpus/scene/seed.json"
for s in "0:5" ":3" "2:" "1,2,3,4" "0,0,16,16"; do printf '\011%s' "$s" > "$corpus/cli_parsers/$s"; done
if [ -d ../shared/repro ]; then
    cp ../shared/repro/*.exr "$corpus/exr/" 2>/dev/null || true
    cp ../shared/repro/camera-*.h "$corpus/camera_header/" 2>/dev/null || true
    cp ../shared/repro/render-*.json "$corpus/scene/" 2>/dev/null || true
    for f in ../shared/repro/manifest-*.json; do
        [ -f "$f" ] && { printf '\001'; cat "$f"; } > "$corpus/layouts/$(basename "$f")"
    done
fi
for h in exr camera_header layouts scene cli_parsers; do
    [ -d "tests/fuzz/corpus/$h" ] && cp tests/fuzz/corpus/$h/* "$corpus/$h/" 2>/dev/null || true
done

mkdir -p build-fuzz/findings
# The harnesses run side by side, one per core (each is single-threaded).
run_harness() {
    local h=$1
    if ./build-fuzz/fuzz_$h "$corpus/$h" -max_total_time="$seconds" -timeout=10 \
        -rss_limit_mb=2048 -malloc_limit_mb=1024 -print_final_stats=1 -seed="${FUZZ_SEED:-0}" \
        -artifact_prefix=build-fuzz/findings/"$h"- > "build-fuzz/fuzz_$h.log" 2>&1; then
        echo pass > "build-fuzz/fuzz_$h.status"
    else
        echo finding > "build-fuzz/fuzz_$h.status"
    fi
}
for h in "${harnesses[@]}"; do
    rm -f "build-fuzz/fuzz_$h.status"
    run_harness "$h" &
    while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do wait -n || true; done
done
wait
status=0
passed=0
failed=0
for h in "${harnesses[@]}"; do
    log=build-fuzz/fuzz_$h.log
    if [ "$(cat "build-fuzz/fuzz_$h.status" 2>/dev/null)" = pass ]; then
        runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
        echo "fuzz_$h: no findings in ${seconds} s, $runs executions ($((runs / seconds))/s)"
        passed=$((passed + 1))
    else
        echo "fuzz_$h: FINDING (see $log and build-fuzz/findings/)"
        tail -30 "$log"
        status=1
        failed=$((failed + 1))
    fi
done
echo "fuzz: $passed passed, $failed failed"
exit $status
