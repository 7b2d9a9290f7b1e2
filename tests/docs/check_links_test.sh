#!/usr/bin/env bash
# Self-test of check_links.py: a scratch repository whose README.md holds a broken link must fail
# (exit 1, naming the file, the line and the link); one whose links all resolve must pass (exit 0).
#   bash tests/docs/check_links_test.sh
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
python=${PYTHON:-/usr/bin/python3}
[ -x "$python" ] || python=python3
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
fail() { echo "check_links_test: $*" >&2; exit 1; }
# Runs the checker on a scratch repository: its output in $out, its exit status in $rc.
check() { out=$("$python" "$here/check_links.py" "$1" 2>&1) && rc=0 || rc=$?; }

# A broken one: a missing file, and a missing anchor in a page that exists.
mkdir -p "$scratch/bad/docs"
printf '# Bad\n\nSee [the guide](docs/guide.md).\n\nAnd [a section](docs/page.md#no-such-heading).\n' \
    > "$scratch/bad/README.md"
printf '# Page\n\n## A heading\n' > "$scratch/bad/docs/page.md"
check "$scratch/bad"
[ $rc -eq 1 ] || fail "a broken link gave exit $rc, not 1: $out"
grep -q 'README.md:3: broken link docs/guide.md' <<<"$out" || fail "the broken link is not named: $out"
grep -q 'README.md:5: broken anchor docs/page.md#no-such-heading' <<<"$out" ||
    fail "the broken anchor is not named: $out"

# Too long a README.
mkdir -p "$scratch/long"
{ echo '# Long'; for i in $(seq 1 150); do echo "line $i"; done; } > "$scratch/long/README.md"
check "$scratch/long"
[ $rc -eq 1 ] || fail "a 151-line README gave exit $rc, not 1: $out"
grep -q 'README.md: 151 lines' <<<"$out" || fail "the length is not named: $out"

# A good one: a file, a folder, an image, HTML, anchors here and in another page (a repeated
# heading's second anchor among them), external links, and link-like text in code.
mkdir -p "$scratch/good/docs/images" "$scratch/good/docs/filters"
: > "$scratch/good/docs/images/a.png"
cat > "$scratch/good/README.md" <<'EOF'
# Good

![a picture](docs/images/a.png) <img src="docs/images/a.png" alt="x"> <a href="docs/">docs</a>
[Filters](docs/filters/bmfr.md#beyond-the-paper-taa-from-the-same-surface---taa-same-surface),
[the second Notes](docs/filters/bmfr.md#notes-1), [here](#usage), [web](https://example.com),
[mail](mailto:someone@example.com), `[not a link](nowhere.md)`.

## Usage

```sh
bmfr render [--width --height](not/a/link.md)
```
EOF
cat > "$scratch/good/docs/filters/bmfr.md" <<'EOF'
# BMFR

## Beyond the paper: TAA from the same surface (`--taa-same-surface`)

## Notes

## Notes

Back to [the front page](../../README.md#good).
EOF
out=$("$python" "$here/check_links.py" "$scratch/good" 2>&1) || fail "good links failed: $out"
grep -q '2 file(s), 7 link(s) checked' <<<"$out" || fail "unexpected summary: $out"
echo "check_links_test: passed"
