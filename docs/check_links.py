#!/usr/bin/env python3
"""Checks the Markdown links of README.md and docs/: every relative link's file
exists, and every #anchor names a heading of its target (GitHub's slug rules).
Run from the repository root: python3 docs/check_links.py; exit 1 on a broken link."""
import os, re, sys

def slug(heading):
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)  # drop punctuation, keep word chars, '-' and spaces
    return s.replace(" ", "-")

def anchors(path):
    out, fence = set(), False
    for line in open(path, encoding="utf-8"):
        if line.startswith("```"):
            fence = not fence
        m = None if fence else re.match(r"#+\s+(.*)", line)
        if m:
            out.add(slug(m.group(1)))
    return out

def files():
    yield "README.md"
    for root, _, names in os.walk("docs"):
        for n in names:
            if n.endswith(".md"):
                yield os.path.join(root, n)

bad = 0
for f in files():
    text = open(f, encoding="utf-8").read()
    text = re.sub(r"```.*?```", "", text, flags=re.S)  # links in code blocks are not links
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+://|mailto:", target):
            continue
        path, _, anchor = target.partition("#")
        full = os.path.normpath(os.path.join(os.path.dirname(f), path)) if path else f
        if not os.path.exists(full):
            print(f"{f}: {target}: no such file"); bad += 1
        elif anchor and full.endswith(".md") and anchor not in anchors(full):
            print(f"{f}: {target}: no such heading"); bad += 1
print(f"{'broken links: ' + str(bad) if bad else 'all links resolve'}")
sys.exit(1 if bad else 0)
