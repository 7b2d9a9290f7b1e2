#!/usr/bin/env bash
# Self-test of check_exports.sh on a real shared libbmfr, through an `nm` wrapper that edits its
# symbol list. The list as it is must pass, and so must one with 20,000 more public symbols
# (more than a pipe holds: grep -q stops reading at its first match, and under pipefail the
# writer's SIGPIPE once failed the check). One without bmfr::libraryVersion, or with a symbol
# outside namespace bmfr, must fail and name it.
#   bash tests/install/check_exports_test.sh LIBRARY.so
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
so=$1
real_nm=$(command -v nm)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
fail() { echo "check_exports_test: $*" >&2; exit 1; }
# Runs the checker with nm's lines matching DROP removed and the file ADD appended: its output in
# $out, its exit status in $rc.
check() {
    printf '%s\n' "$2" > "$scratch/add"
    cat > "$scratch/nm" <<WRAPPER
#!/bin/sh
"$real_nm" "\$@" | grep -v -e '$1'
cat "$scratch/add"
WRAPPER
    chmod +x "$scratch/nm"
    out=$(PATH="$scratch:$PATH" bash "$here/check_exports.sh" "$so" 2>&1) && rc=0 || rc=$?
}

check '^$' ''
[ $rc -eq 0 ] || fail "the library as built gave exit $rc: $out"

check '^$' "$(seq 20000 | sed 's/.*/0000000000001000 T bmfr::padding&()/')"
[ $rc -eq 0 ] || fail "the list with 20,000 more symbols gave exit $rc: $out"
grep -q 'exported symbols: 20[0-9][0-9][0-9]$' <<<"$out" || fail "the long list was not counted: $out"

check 'libraryVersion' ''
[ $rc -eq 1 ] || fail "a list without libraryVersion gave exit $rc, not 1: $out"
grep -q 'bmfr::libraryVersion is not exported' <<<"$out" || fail "the missing symbol is not named: $out"

check '^$' '0000000000001000 T leaked_helper'
[ $rc -eq 1 ] || fail "a symbol outside namespace bmfr gave exit $rc, not 1: $out"
grep -q '^leaked_helper$' <<<"$out" || fail "the leaked symbol is not named: $out"
echo "check_exports_test: passed"
