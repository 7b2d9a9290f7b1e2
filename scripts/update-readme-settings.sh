#!/usr/bin/env bash
# Replaces README.md's settings table with `bmfr settings --markdown` (run after changing a
# filter's settings table; a test fails while they differ).
set -euo pipefail
cd "$(dirname "$0")/.."
export table=$(./build/bmfr settings --markdown)
awk '
    /<!-- settings-table:begin/ { print; print ENVIRON["table"]; skip = 1; next }
    /<!-- settings-table:end/ { skip = 0 }
    !skip' README.md > README.md.tmp
mv README.md.tmp README.md
