#!/usr/bin/env bash
# The quality tables of docs/results/ (the rooms page), from scratch: renders the small rooms
# (room-dark, room-light), cornell-moving, and the rooms seen by a still camera without jitter
# (scripts/scenes/*-static.json: there the temporal error is flicker alone) at 256x192, 24
# frames, 64-spp references, in the original layout (no emission buffer), runs each method on
# them and scores frames 8 to 23.
#
#   bash scripts/quality-tables.sh [WORK_DIR] [SEQUENCE ...]   # default /tmp/bmfr-quality-tables
#   REFERENCE_SPP=1024 bash scripts/quality-tables.sh /tmp/qt1k room-dark room-light cornell-moving
#   REFERENCE_SPP=1024 JITTER=off LAYOUT=manifest bash scripts/quality-tables.sh /tmp/qt room-dark
#
# JITTER=on|off (default: the scene's own) renders with or without the frames' sub-pixel offsets;
# LAYOUT=manifest|bmfr (default bmfr) the layout, manifest with the emission and visibility
# buffers; SIZE=WxH (default 256x192) the frames' size.
# A SEQUENCE is a preset, a scene description file, or a folder that holds a rendered sequence
# with references (a Cycles one from tools/blender/render_sequence.py, say), scored as it is.
# About three minutes on 2 cores (REFERENCE_SPP 1024: about 4.5 minutes per sequence more). Prints one Markdown table per sequence: tone-mapped
# RMSE (and its ratio to the noisy input's), SSIM, FLIP, temporal error and change error, and the
# reference's own temporal error. The change error needs a converged reference: a 64-spp
# reference's own noise makes up most of it.
set -euo pipefail
cd "$(dirname "$0")/.."
bmfr=$PWD/build/bmfr
[ -x "$bmfr" ] || { echo "no build/bmfr: run bash scripts/build.sh first" >&2; exit 1; }
work=${1:-/tmp/bmfr-quality-tables}
spp=${REFERENCE_SPP:-64}
layout=${LAYOUT:-bmfr}
size=${SIZE:-256x192}
jitter=()
[ -z "${JITTER:-}" ] || jitter=(--jitter "$JITTER")
shift || true
sequences=("$@")
[ ${#sequences[@]} -gt 0 ] ||
    sequences=(room-dark room-light cornell-moving scripts/scenes/room-dark-static.json
        scripts/scenes/room-light-static.json)
mkdir -p "$work"

# name: the denoise options (bmfr and svgf: their defaults, the quality preset)
methods=(
    "bmfr:"
    "bmfr-no-taa:--taa false"
    "bmfr-authors-taa:--taa-motion-weight false"
    "bmfr-faithful:--preset faithful"
    "bmfr-faithful-no-taa:--preset faithful --taa false"
    "bmfr-no-visibility:--visibility-feature false --visibility-taps false"
    "svgf:--filter svgf"
    "svgf-faithful:--filter svgf --preset faithful"
    "walr:--filter walr"
    "mara2017:--filter mara2017"
    "accumulation:--preset faithful --fitting false --taa false"
)

for scene in "${sequences[@]}"; do
    seq=$(basename "$scene" .json)${JITTER:+-jitter-$JITTER}
    dir=$work/$seq
    input=$dir/input
    if [ -f "$scene/sequence.json" ]; then
        input=$(cd "$scene" && pwd)
        mkdir -p "$dir"
    elif [ ! -f "$dir/.done" ]; then
        echo "rendering $seq ..." >&2
        rm -rf "$dir"
        "$bmfr" render -o "$dir/input" -s "$scene" --width "${size%x*}" --height "${size#*x}" \
            --frames 24 --reference-spp "$spp" --layout "$layout" "${jitter[@]}" -q
        touch "$dir/.done"
    fi
    args=()
    for m in "${methods[@]}"; do
        name=${m%%:*}
        # shellcheck disable=SC2086 # the options are words
        "$bmfr" denoise "$input" -o "$dir/$name" ${m#*:} -q --no-png --no-flip --overwrite
        args+=("$name=$dir/$name")
    done
    "$bmfr" eval -r "$input" -m noisy "${args[@]}" -o "$dir/eval" --frames 8:24 --json -q \
        > "$dir/scores.json"
    /usr/bin/python3 - "$seq" "$dir/scores.json" "$spp" "${methods[@]%%:*}" noisy <<'EOF'
import json, sys
seq, path, spp, order = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
scores = json.load(open(path))
methods = scores["methods"]
noisy = methods["noisy"]["mean"]["rmse"]
print(f"\n| {seq} | RMSE (of noisy) | SSIM | FLIP | temporal | change |\n|---|---|---|---|---|---|")
for m in order:
    s = methods[m]["mean"]
    print(f"| {m} | {s['rmse']:.5f} ({s['rmse'] / noisy:.3f}) | {s['ssim']:.4f} | "
          f"{s['flip']:.4f} | {s['temporal_error']:.5f} | {s['temporal_change_error']:.5f} |")
print(f"| reference ({spp} spp) | | | | {scores['reference_temporal_error']:.5f} | |")
EOF
done
