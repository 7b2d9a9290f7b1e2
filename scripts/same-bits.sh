#!/usr/bin/env bash
# Checks that two builds of bmfr give byte-identical outputs: four small sequences (a moving
# camera, moving objects with motion vectors, the same with Mara's factored paths, a lamp in
# view) rendered by OLD, then denoised by both with every filter, both presets and both host
# backends, with the debug buffers; every EXR compared. For refactors that must not change bits.
#   same-bits.sh OLD_BMFR NEW_BMFR [WORK_DIR]
set -euo pipefail
old=$1 new=$2 work=${3:-$(mktemp -d)}
mkdir -p "$work/seq"
render() { [ -d "$work/seq/$1" ] || "$old" render -o "$work/seq/$1" "${@:2}" --no-reference -q; }
render camera -s cornell-moving --width 80 --height 60 --frames 6
render objects -s cornell-objects-moving --width 80 --height 60 --frames 6
render factored -s cornell-objects-moving --paths mara --width 80 --height 60 --frames 6
render lamp -s room-light --width 96 --height 72 --frames 6
runs=0
# The renders are kept for a second call; the outputs are made again (denoise refuses a folder
# holding an earlier run's outputs, and OLD may predate --overwrite).
rm -rf "$work/old" "$work/new"
for bin in old new; do
    exe=$old
    [ $bin = new ] && exe=$new
    for seq in "$work"/seq/*; do
        for f in bmfr svgf walr mara2017; do
            for p in faithful quality; do
                for b in reference cpu; do
                    o="$work/$bin/$(basename "$seq")/$f-$p-$b"
                    "$exe" denoise "$seq" -o "$o" --filter $f --backend $b --preset $p --debug \
                        --no-png -q > /dev/null 2>> "$work/warnings.log"
                    runs=$((runs + 1))
                done
            done
        done
    done
done
differ=$(diff -rq "$work/old" "$work/new" | grep -v 'report.json' || true)
exrs=$(find "$work/new" -name '*.exr' | wc -l)
if [ -n "$differ" ]; then
    echo "$differ" >&2
    echo "same-bits: outputs differ ($exrs EXRs, $((runs / 2)) runs per build)" >&2
    exit 1
fi
echo "same-bits: $exrs EXRs byte-identical ($((runs / 2)) runs per build, in $work)"
