#!/usr/bin/env bash
# Two runs of one command into one output folder at once (../shared/repro/
# concurrent-denoise-same-output.sh, for denoise, render and eval): the second must be refused at
# once (exit 1, "another run is writing to", naming the first), the first must exit 0 with
# outputs byte-identical to its own solo run. Usage: concurrent_writers.sh BMFR WORK_FOLDER
set -uo pipefail
B=$1
W=$2
rm -rf "$W"
mkdir -p "$W"
"$B" synth -o "$W/seq" --width 160 --height 90 --frames 60 -q || exit 1

# pair NAME "ARGS_A" "ARGS_B" FILE...: OUT in the arguments stands for the output folder. A
# starts first; B starts once A holds the folder (its lock file names it), while A still runs.
pair() {
    local name=$1 a=$2 b=$3
    shift 3
    local out=$W/$name.both
    "$B" ${a//OUT/$W/$name.solo_a} > "$W/$name.solo_a.log" 2>&1 || { echo "$name: solo run A failed"; return 1; }
    "$B" ${a//OUT/$out} > "$W/$name.a.log" 2>&1 &
    local pa=$!
    for _ in $(seq 1 1000); do
        [ -s "$out/.bmfr-lock" ] && break
        kill -0 $pa 2> /dev/null || break
        sleep 0.01
    done
    "$B" ${b//OUT/$out} > "$W/$name.b.log" 2>&1
    local rb=$?
    wait $pa
    local ra=$?
    if [ $ra -ne 0 ] || [ $rb -ne 1 ]; then
        echo "$name: FAILED: exit codes $ra (first run) and $rb (second run); expected 0 and 1"
        cat "$W/$name.a.log" "$W/$name.b.log"
        return 1
    fi
    if ! grep -q "another run is writing to $out (pid $pa: " "$W/$name.b.log"; then
        echo "$name: FAILED: the refused run does not name the first:"
        cat "$W/$name.b.log"
        return 1
    fi
    for f in "$@"; do
        if ! cmp -s "$W/$name.solo_a/$f" "$out/$f"; then
            echo "$name: FAILED: $f differs from the solo run's"
            return 1
        fi
    done
    echo "$name: the second run was refused, the first's $# files equal its solo run's"
}

frames=()
for i in $(seq -f %04g 0 59); do frames+=("denoised_$i.exr"); done
status=0
pair denoise "denoise $W/seq -o OUT -q --no-flip --no-png" \
    "denoise $W/seq -o OUT --seed 1 -q --no-flip --no-png" "${frames[@]}" || status=1
pair render "render --scene cornell-moving --width 64 --height 48 --frames 6 --reference-spp 64 -o OUT -q" \
    "render --scene cornell-moving --width 64 --height 48 --frames 6 --reference-spp 64 --seed 7 -o OUT -q" \
    color_0000.exr color_0005.exr reference_0005.exr || status=1
pair eval "eval -r $W/seq -m noisy -m bmfr=$W/denoise.solo_a -o OUT -q" \
    "eval -r $W/seq -m noisy -o OUT -q --no-flip" \
    table.csv per_frame.csv frames.png || status=1
[ $status -eq 0 ] && echo "concurrent writers passed"
exit $status
