#!/usr/bin/env bash
# Checks that a shared libbmfr exports the public API only: namespace bmfr (with its typeinfo
# and vtables) and none of the internals. Runs PROGRAM (linked against it) when given.
#   check_exports.sh LIBRARY.so [PROGRAM]
set -euo pipefail
so=$1
[ -f "$so" ] || { echo "no shared library at '$so'" >&2; exit 1; }
if [ $# -ge 2 ]; then "$2"; fi
exports=$(nm -D --defined-only -C "$so" | awk '{ $1 = ""; $2 = ""; print }' | sed 's/^ *//')
echo "exported symbols: $(echo "$exports" | grep -c .)"
public='^(bmfr::|typeinfo (name )?for bmfr::|vtable for bmfr::)'
if echo "$exports" | grep -v -E "$public" | grep -q .; then
    echo "symbols outside namespace bmfr are exported:" >&2
    echo "$exports" | grep -v -E "$public" | head -20 >&2
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
    echo "$exports" | grep -q -F "$api" || { echo "$api is not exported" >&2; exit 1; }
done
echo "exports: public API only"
