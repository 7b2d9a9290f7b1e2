#!/usr/bin/env bash
# The comparison with Intel Open Image Denoise of docs/results/ (the OIDN page), from scratch:
# renders the built-in sequences at 256x192, 24 frames, with 1024-spp references (a moving
# camera, moving objects, a lamp in view, and the lamp in view without jitter), runs the four
# filters and OIDN (`bmfr peer oidn`: its defaults, and its fast settings) on each, scores frames
# 8 to 23 with `bmfr eval` and prints one Markdown table per sequence, then one of the geometric
# means over the sequences.
#
#   bash scripts/compare-oidn.sh [WORK_DIR] [SEQUENCE ...]   # default /tmp/bmfr-compare-oidn
#
# A SEQUENCE is a preset, a scene description file, or a sequence folder rendered elsewhere (as
# tools/blender/render_sequence.py writes; scored as it is, without Mara). FRAMES (default 8:24)
# picks the frames scored. Needs build/bmfr and OIDN
# (scripts/install-oidn.sh). About 7 minutes per sequence on 2 cores, most of it the reference.
# Mara et al. 2017 filters its own factored paths: its input is the same scene rendered with
# `--paths mara` (other noise, same reference), scored against the same reference.
set -euo pipefail
# Paths given relative to where the script is run from, before it moves to the repository.
work=$(realpath -m "${1:-/tmp/bmfr-compare-oidn}")
shift || true
sequences=()
for a in "$@"; do
    if [ -e "$a" ]; then sequences+=("$(realpath "$a")"); else sequences+=("$a"); fi # a preset
done
cd "$(dirname "$0")/.."
bmfr=$PWD/build/bmfr
[ -x "$bmfr" ] || { echo "no build/bmfr: run bash scripts/build.sh first" >&2; exit 1; }
[ ${#sequences[@]} -gt 0 ] ||
    sequences=(cornell-moving cornell-objects room-light "$PWD/scripts/scenes/room-light-unjittered.json")
mkdir -p "$work"
FRAMES=${FRAMES:-8:24}

# name: the command and its options (INPUT is the sequence, MARA_INPUT its factored-path render)
methods=(
    "bmfr:denoise INPUT"
    "bmfr faithful:denoise INPUT --preset faithful"
    "svgf:denoise INPUT --filter svgf"
    "walr:denoise INPUT --filter walr"
    "mara2017:denoise MARA_INPUT --filter mara2017"
    "oidn:peer oidn INPUT"
    "oidn fast:peer oidn INPUT --quality fast --prefilter none"
)

tables=()
for scene in "${sequences[@]}"; do
    seq=$(basename "$scene" .json)
    dir=$work/$seq
    input=$dir/input
    if [ -f "$scene/sequence.json" ]; then
        # A sequence rendered elsewhere (Blender Cycles): no factored paths, so no Mara row.
        input=$(cd "$scene" && pwd)
    elif [ ! -f "$dir/.done" ]; then
        echo "rendering $seq (1024-spp reference) ..." >&2
        rm -rf "$dir"
        "$bmfr" render -o "$input" -s "$scene" --width 256 --height 192 --frames 24 \
            --reference-spp 1024 -q
        "$bmfr" render -o "$dir/mara_input" -s "$scene" --width 256 --height 192 --frames 24 \
            --paths mara --no-reference -q
        touch "$dir/.done"
    fi
    args=()
    for m in "${methods[@]}"; do
        name=${m%%:*}
        out="$dir/out/${name// /_}"
        # The method's words, with INPUT and MARA_INPUT replaced as whole words (paths may hold
        # spaces or any character).
        read -ra words <<< "${m#*:}"
        skip=false
        for k in "${!words[@]}"; do
            case ${words[k]} in
            INPUT) words[k]=$input ;;
            MARA_INPUT) if [ -d "$dir/mara_input" ]; then words[k]=$dir/mara_input; else skip=true; fi ;;
            esac
        done
        $skip && continue
        echo "$seq: $name" >&2
        "$bmfr" "${words[@]}" -o "$out" -q --no-png --no-flip --overwrite
        args+=("$name=$out")
    done
    "$bmfr" eval -r "$input" -m noisy "${args[@]}" -o "$dir/eval" --frames "$FRAMES" --json -q \
        > "$dir/scores.json"
    tables+=("$seq=$dir/scores.json")
done
/usr/bin/python3 - "${tables[@]}" -- noisy "${methods[@]%%:*}" <<'PY'
import json, math, sys
split = sys.argv.index("--")
runs = [(a.split("=", 1)[0], json.load(open(a.split("=", 1)[1]))) for a in sys.argv[1:split]]
order = sys.argv[split + 1:]  # the methods in the script's order (JSON objects come sorted)
cols = [("rmse", "RMSE", "{:.4f}"), ("ssim", "SSIM", "{:.4f}"), ("flip", "FLIP", "{:.4f}"),
        ("temporal_error", "temporal", "{:.4f}"), ("temporal_change_error", "change", "{:.4f}")]
head = "| {} | " + " | ".join(c[1] for c in cols) + " | ms/frame |\n|---|" + "---|" * (len(cols) + 1)
for seq, s in runs:
    print("\n" + head.format(seq))
    for m in [m for m in order if m in s["methods"]]:
        v = s["methods"][m]["mean"]
        ms = s["methods"][m].get("ms_per_frame")
        print(f"| {m} | " + " | ".join(f.format(v[k]) for k, _, f in cols) +
              f" | {'-' if ms is None else f'{ms:.1f}'} |")
    print(f"| reference | | | | {s['reference_temporal_error']:.4f} | | |")
    machines = {s["methods"][m].get("machine") for m in s["methods"]} - {None}
    print(f"\nms/frame on {', '.join(sorted(machines))}; frames {s['frames'][0]}:{s['frames'][1]}")
if len(runs) > 1:
    print("\n" + head.format("geometric mean"))
    for m in order:
        cells = []
        for k, _, f in cols + [("ms_per_frame", "", "{:.1f}")]:
            vals = [(s["methods"][m]["mean"].get(k) if k != "ms_per_frame"
                     else s["methods"][m].get(k)) if m in s["methods"] else None for _, s in runs]
            ok = [x for x in vals if x is not None and x > 0]
            cells.append(f.format(math.exp(sum(map(math.log, ok)) / len(ok))) if len(ok) == len(vals) else "-")
        print(f"| {m} | " + " | ".join(cells) + " |")
PY
