#!/usr/bin/env python3
"""Checks that every relative link and #anchor in README.md and docs/*.md resolves.

A link [text](target) or ![alt](target) outside code resolves when target (relative to the file
holding it) exists and, for a #anchor, when the Markdown file it names has a heading whose GitHub
anchor is that one, or an explicit <a name="..."> / id="...". GitHub's anchor rule: the heading's
text (links reduced to their text, inline code to its content) lower-cased, every character that
is not a letter, digit, space, hyphen or underscore dropped, spaces turned into hyphens; a repeat
gets -1, -2, ... Web links (http, https, mailto) are not fetched.

  scripts/check_doc_links.py [REPO_ROOT]     exit 0 when all resolve, 1 listing those that do not
"""

import os
import re
import sys

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
EXPLICIT = re.compile(r"<a\s+(?:name|id)=\"([^\"]+)\"|\sid=\"([^\"]+)\"")
FENCE = re.compile(r"^\s*(```|~~~)")


def lines_outside_fences(text):
    """(line number, line) of the lines outside fenced code blocks."""
    fenced = None
    for number, line in enumerate(text.splitlines(), 1):
        match = FENCE.match(line)
        if match:
            if fenced is None:
                fenced = match.group(1)
            elif match.group(1) == fenced:
                fenced = None
            continue
        if fenced is None:
            yield number, line


def github_anchor(heading):
    text = re.sub(r"!?\[((?:[^\[\]]|\[[^\]]*\])*)\]\([^)]*\)", r"\1", heading)
    text = text.lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def anchors_of(path, cache={}):
    if path not in cache:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        anchors, seen = set(), {}
        for _, line in lines_outside_fences(text):
            match = HEADING.match(line)
            if match:
                anchor = github_anchor(match.group(2))
                count = seen.get(anchor, 0)
                seen[anchor] = count + 1
                anchors.add(anchor if count == 0 else "%s-%d" % (anchor, count))
            for explicit in EXPLICIT.finditer(line):
                anchors.add(explicit.group(1) or explicit.group(2))
        cache[path] = anchors
    return cache[path]


def without_code_spans(line):
    return re.sub(r"(`+)(?:(?!\1).)*\1", "", line)


def check(root):
    files = [os.path.join(root, "README.md")]
    docs = os.path.join(root, "docs")
    files += sorted(os.path.join(docs, name) for name in os.listdir(docs) if name.endswith(".md"))
    broken = []
    for path in files:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for number, line in lines_outside_fences(text):
            for match in LINK.finditer(without_code_spans(line)):
                target = match.group(1)
                if not target or re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):
                    continue
                file_part, _, anchor = target.partition("#")
                resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) \
                    if file_part else path
                where = "%s:%d: %s" % (os.path.relpath(path, root), number, target)
                if not os.path.exists(resolved):
                    broken.append(where + " (no such file)")
                elif anchor and resolved.endswith(".md") and anchor not in anchors_of(resolved):
                    broken.append(where + " (no such anchor)")
    return broken


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), ".."))
    broken = check(root)
    for line in broken:
        print(line)
    if broken:
        print("%d broken link(s) in README.md and docs/" % len(broken))
        return 1
    print("every relative link and anchor in README.md and docs/ resolves")
    return 0


if __name__ == "__main__":
    sys.exit(main())
