#!/usr/bin/env bash
# Two runs of one command into one output folder at once (../shared/repro/
# concurrent-denoise-same-output.sh, for denoise, render and eval): one must be refused at once
# (exit 1, "another run is writing to"), the other must exit 0 with outputs byte-identical to
# its own solo run. Usage: concurrent_writers.sh BMFR WORK_FOLDER
set -uo pipefail
B=$1
W=$2
rm -rf "$W"
mkdir -p "$W"
"$B" synth -o "$W/seq" --width 160 --height 90 --frames 30 -q || exit 1

# pair NAME "ARGS_A" "ARGS_B" FILE...: OUT in the arguments stands for the output folder.
pair() {
    local name=$1 a=$2 b=$3
    shift 3
    local out=$W/$name.both
    "$B" ${a//OUT/$W/$name.solo_a} > "$W/$name.solo_a.log" 2>&1 || { echo "$name: solo run A failed"; return 1; }
    "$B" ${b//OUT/$W/$name.solo_b} > "$W/$name.solo_b.log" 2>&1 || { echo "$name: solo run B failed"; return 1; }
    "$B" ${a//OUT/$out} > "$W/$name.a.log" 2>&1 &
    local pa=$!
    "$B" ${b//OUT/$out} > "$W/$name.b.log" 2>&1 &
    local pb=$!
    wait $pa
    local ra=$?
    wait $pb
    local rb=$?
    local winner refused
    if [ $ra -eq 0 ] && [ $rb -eq 1 ]; then
        winner=solo_a refused=b
    elif [ $ra -eq 1 ] && [ $rb -eq 0 ]; then
        winner=solo_b refused=a
    else
        echo "$name: FAILED: exit codes $ra and $rb (expected one 0 and one 1)"
        cat "$W/$name.a.log" "$W/$name.b.log"
        return 1
    fi
    if ! grep -q "another run is writing to $out" "$W/$name.$refused.log"; then
        echo "$name: FAILED: the refused run does not say why:"
        cat "$W/$name.$refused.log"
        return 1
    fi
    for f in "$@"; do
        if ! cmp -s "$W/$name.$winner/$f" "$out/$f"; then
            echo "$name: FAILED: $f differs from the solo run's"
            return 1
        fi
    done
    echo "$name: one run refused, the other's $# files equal to its solo run's"
}

frames=()
for i in $(seq -f %04g 0 29); do frames+=("denoised_$i.exr"); done
status=0
pair denoise "denoise $W/seq -o OUT -q --no-flip --no-png" \
    "denoise $W/seq -o OUT --seed 1 -q --no-flip --no-png" "${frames[@]}" || status=1
pair render "render --scene cornell-moving --width 48 --height 32 --frames 4 --reference-spp 16 -o OUT -q" \
    "render --scene cornell-moving --width 48 --height 32 --frames 4 --reference-spp 16 --seed 7 -o OUT -q" \
    color_0000.exr color_0003.exr reference_0003.exr || status=1
pair eval "eval -r $W/seq -m noisy -o OUT -q --no-flip" \
    "eval -r $W/seq -m noisy -m bmfr=$W/denoise.solo_a -o OUT -q --no-flip" \
    table.csv per_frame.csv frames.png || status=1
[ $status -eq 0 ] && echo "concurrent writers passed"
exit $status
