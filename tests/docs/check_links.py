#!/usr/bin/env python3
"""Checks the documentation's relative links: README.md and every docs/**/*.md.

    python3 tests/docs/check_links.py REPO_ROOT

Every relative Markdown link and image ([text](path), ![alt](path)) and every HTML
<img src="..."> and <a href="..."> that is not http(s):, mailto: or a pure #anchor must name a
file or folder that exists, resolved against the page that holds it. A #fragment into a .md file
(the same page or another) must name one of that page's headings, as GitHub makes their anchors:
lowercase, punctuation other than - and _ dropped, each space a -, and a repeated heading's anchor
suffixed -1, -2, ... Links inside fenced code blocks and `code spans` are not links. README.md may
have at most 150 lines.

Exit status 0 with a one-line summary when everything holds; 1 with one `file:line: problem` line
per problem otherwise; 2 on a usage error. Python 3 standard library only.
"""
import os
import re
import sys
import unicodedata
from urllib.parse import unquote

README_MAX_LINES = 150

# [text](target) and ![alt](target); the target may be <in angle brackets> and may carry a
# "title". Nested brackets in the text (an image inside a link) are allowed one level deep.
MD_LINK = re.compile(
    r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*(<[^>\n]*>|[^\s()]*(?:\([^\s()]*\)[^\s()]*)*)"
    r"(?:\s+(?:\"[^\"]*\"|'[^']*'|\([^)]*\)))?\s*\)"
)
HTML_LINK = re.compile(r"<(?:img|a)\b[^>]*?\b(?:src|href)\s*=\s*(\"[^\"]*\"|'[^']*'|[^\s>]+)",
                       re.IGNORECASE)
FENCE = re.compile(r"^\s{0,3}(`{3,}|~{3,})")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
HTML_ANCHOR = re.compile(r"<a\b[^>]*\b(?:name|id)\s*=\s*[\"']([^\"']+)[\"']", re.IGNORECASE)
EXTERNAL = re.compile(r"^(?:https?:|mailto:)", re.IGNORECASE)


def strip_code_spans(line):
    """Blanks `code spans` (keeping columns), so links inside them are not seen."""
    out, i = [], 0
    while i < len(line):
        if line[i] == "`":
            j = i
            while j < len(line) and line[j] == "`":
                j += 1
            ticks = line[i:j]
            end = line.find(ticks, j)
            if end < 0:
                out.append(line[i:j])
                i = j
                continue
            out.append(" " * (end + len(ticks) - i))
            i = end + len(ticks)
        else:
            out.append(line[i])
            i += 1
    return "".join(out)


def prose_lines(text):
    """(line number, line, the line with its code spans blanked) for each line outside fenced
    code blocks."""
    fence = None
    for number, line in enumerate(text.split("\n"), 1):
        m = FENCE.match(line)
        if fence is None:
            if m:
                fence = m.group(1)
                continue
            yield number, line, strip_code_spans(line)
        elif m and m.group(1)[0] == fence[0] and len(m.group(1)) >= len(fence) \
                and line.strip() == m.group(1):
            fence = None


def heading_text(raw):
    """A heading's text as GitHub renders it: links by their text, no emphasis or code marks."""
    text = re.sub(r"!?\[((?:[^\[\]]|\[[^\[\]]*\])*)\]\([^)]*\)", r"\1", raw)
    text = re.sub(r"<[^>]+>", "", text)
    text = text.replace("`", "")
    text = re.sub(r"(\*\*|__)(.+?)\1", r"\2", text)
    text = re.sub(r"(?<![\w*])([*_])(?!\s)(.+?)(?<!\s)\1(?![\w*])", r"\2", text)
    return text


def slug(raw):
    """GitHub's anchor for a heading: lowercase, punctuation but - and _ dropped, spaces to -."""
    kept = []
    for ch in heading_text(raw).strip().lower():
        if ch in "-_ ":
            kept.append(ch)
        elif unicodedata.category(ch)[0] in "LNM":
            kept.append(ch)
    return "".join(kept).replace(" ", "-")


_anchor_cache = {}


def anchors_of(path):
    """Every anchor a Markdown file defines: its headings' slugs (repeats numbered) and any
    <a name="..."> or <a id="...">."""
    if path not in _anchor_cache:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        seen, anchors = {}, set()
        for _, line, prose in prose_lines(text):
            m = HEADING.match(line)
            if m:
                base = slug(m.group(2))
                n = seen.get(base, 0)
                seen[base] = n + 1
                anchors.add(base if n == 0 else "%s-%d" % (base, n))
            for a in HTML_ANCHOR.findall(prose):
                anchors.add(a)
        _anchor_cache[path] = anchors
    return _anchor_cache[path]


def links_in(text):
    """(line number, target) for every link and image target outside code."""
    for number, _, line in prose_lines(text):
        for m in MD_LINK.finditer(line):
            target = m.group(1)
            if target.startswith("<") and target.endswith(">"):
                target = target[1:-1]
            yield number, target.strip()
        for m in HTML_LINK.finditer(line):
            target = m.group(1)
            if target[:1] in "\"'":
                target = target[1:-1]
            yield number, target.strip()


def check_file(root, path, problems):
    """Checks one page's links; returns how many it checked."""
    rel = os.path.relpath(path, root)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    checked = 0
    for number, target in links_in(text):
        if not target or EXTERNAL.match(target):
            continue
        checked += 1
        where = "%s:%d" % (rel, number)
        target_path, _, fragment = target.partition("#")
        target_path = unquote(target_path.split("?", 1)[0])
        fragment = unquote(fragment)
        if target_path:
            if target_path.startswith("/"):
                resolved = os.path.normpath(os.path.join(root, target_path.lstrip("/")))
            else:
                resolved = os.path.normpath(os.path.join(os.path.dirname(path), target_path))
            if not os.path.exists(resolved):
                problems.append("%s: broken link %s (no %s)"
                                % (where, target, os.path.relpath(resolved, root)))
                continue
        else:
            resolved = path
        if fragment and resolved.endswith(".md") and os.path.isfile(resolved):
            if fragment not in anchors_of(resolved):
                problems.append("%s: broken anchor %s (%s has no heading #%s)"
                                % (where, target, os.path.relpath(resolved, root), fragment))
    return checked


def pages(root):
    found = []
    readme = os.path.join(root, "README.md")
    if os.path.isfile(readme):
        found.append(readme)
    docs = os.path.join(root, "docs")
    for folder, dirs, files in os.walk(docs):
        dirs.sort()
        for name in sorted(files):
            if name.endswith(".md"):
                found.append(os.path.join(folder, name))
    return found


def main(argv):
    if len(argv) != 2:
        print("usage: check_links.py REPO_ROOT", file=sys.stderr)
        return 2
    root = os.path.abspath(argv[1])
    if not os.path.isdir(root):
        print("check_links.py: %s is not a folder" % argv[1], file=sys.stderr)
        return 2
    problems, checked = [], 0
    files = pages(root)
    if not files:
        problems.append("README.md: missing, and no docs/*.md either")
    for path in files:
        checked += check_file(root, path, problems)
    readme = os.path.join(root, "README.md")
    if os.path.isfile(readme):
        with open(readme, encoding="utf-8") as f:
            lines = len(f.read().splitlines())
        if lines > README_MAX_LINES:
            problems.append("README.md: %d lines, more than %d: move the rest into docs/"
                            % (lines, README_MAX_LINES))
    if problems:
        for p in problems:
            print(p)
        print("check_links.py: %d problem(s) in %d file(s), %d link(s) checked"
              % (len(problems), len(files), checked))
        return 1
    print("check_links.py: %d file(s), %d link(s) checked, all good" % (len(files), checked))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
