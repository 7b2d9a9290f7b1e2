#!/usr/bin/env bash
# Replaces the settings table of docs/settings.md (between its settings-table markers) with
# `bmfr settings --markdown` (run after changing a filter's settings table; the test
# Cli.SettingsDocTableIsTheGeneratedOne fails while they differ). Needs build/bmfr.
set -euo pipefail
cd "$(dirname "$0")/.."
doc=docs/settings.md
export table=$(./build/bmfr settings --markdown)
awk '
    /<!-- settings-table:begin/ { print; print ENVIRON["table"]; skip = 1; next }
    /<!-- settings-table:end/ { skip = 0 }
    !skip' "$doc" > "$doc.tmp"
mv "$doc.tmp" "$doc"
