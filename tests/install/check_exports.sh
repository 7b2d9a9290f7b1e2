#!/usr/bin/env bash
# Checks that a shared libbmfr exports the public API only: the C API (bmfr.h), namespace bmfr
# (with its typeinfo and vtables) and none of the internals, and lists the C API's symbols. Runs
# each PROGRAM (linked against it) when given.
#   check_exports.sh LIBRARY.so [PROGRAM ...]
set -euo pipefail
so=$1
[ -f "$so" ] || { echo "no shared library at '$so'" >&2; exit 1; }
shift
for program in "$@"; do "$program"; done
exports=$(nm -D --defined-only -C "$so" | awk '{ $1 = ""; $2 = ""; print }' | sed 's/^ *//')
echo "exported symbols: $(echo "$exports" | grep -c .)"
public='^(bmfr[A-Z][A-Za-z]*$|bmfr::|typeinfo (name )?for bmfr::|vtable for bmfr::)'
# Here-strings, not pipes, feed the grep -q checks: grep -q exits at its first match, and under
# pipefail the writer's SIGPIPE would then fail the check (it did, on a loaded CI machine).
outside=$(grep -v -E "$public" <<<"$exports" || true)
if [ -n "$outside" ]; then
    echo "symbols outside namespace bmfr are exported:" >&2
    head -20 <<<"$outside" >&2
    exit 1
fi
# The internals live in namespace bmfr too, so name them.
if echo "$exports" | grep -E 'ThreadPool|Passes|Staging|TemporalHistory|Householder|Impl::|cpu::|reference::|detail::|Image<'; then
    echo "internal symbols are exported" >&2
    exit 1
fi
for api in 'bmfr::makeFilter' 'bmfr::TemporalFilter::denoise' 'bmfr::BmfrDenoiser::BmfrDenoiser' \
           'bmfr::SvgfDenoiser::variance' 'bmfr::libraryVersion' 'bmfr::compiledBackends' \
           'typeinfo for bmfr::TemporalFilter'; do
    grep -q -F "$api" <<<"$exports" || { echo "$api is not exported" >&2; exit 1; }
done
# The C API: every function bmfr.h declares, and nothing else named bmfr[A-Z]*.
declared=$(grep -o 'bmfr[A-Z][A-Za-z]*(' "$(dirname "$0")/../../include/bmfr/bmfr.h" | tr -d '(' | sort -u)
exportedC=$(echo "$exports" | grep -E '^bmfr[A-Z][A-Za-z]*$' | sort -u)
if [ "$declared" != "$exportedC" ]; then
    echo "the C API's exports differ from bmfr.h's functions:" >&2
    diff <(echo "$declared") <(echo "$exportedC") >&2 || true
    exit 1
fi
echo "C API: $(echo "$exportedC" | wc -l) functions: $(echo $exportedC)"
echo "exports: public API only"
