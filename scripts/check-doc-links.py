#!/usr/bin/python3
"""The relative links of README.md, docs/**/*.md and the results gallery (results/*.md): each target exists, and an #anchor into a Markdown file
names one of its headings (GitHub's slugs). Prints each broken link as FILE:LINE and exits 1; web links are
not followed (nothing is fetched).
Usage: scripts/check-doc-links.py [ROOT]   (ROOT: the repository, default this one)"""
import glob
import os
import re
import sys

LINK = re.compile(r"\[(?:[^\]\\]|\\.)*\]\(([^)\s]+)\)")


def slugs(path):
    """The anchors of a Markdown file's headings, numbered as GitHub numbers repeats."""
    out, seen, fence = set(), {}, False
    for line in open(path, encoding="utf-8"):
        if line.startswith("```"):
            fence = not fence
        if fence or not line.startswith("#"):
            continue
        slug = re.sub(r"[^\w\- ]", "", line.lstrip("#").strip().lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        out.add(slug if n == 0 else f"{slug}-{n}")
    return out


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    files = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True))
    files += sorted(glob.glob(os.path.join(root, "results", "*.md")))
    broken = count = 0
    for name in files:
        fence = False
        for number, line in enumerate(open(name, encoding="utf-8"), 1):
            if line.startswith("```"):
                fence = not fence
            if fence or line.startswith("    "):  # code: an example's brackets are no link
                continue
            for target in LINK.findall(line):
                if re.match(r"[a-z]+:", target):
                    continue
                count += 1
                path, _, anchor = target.partition("#")
                full = os.path.normpath(os.path.join(os.path.dirname(name), path)) if path else name
                if not os.path.exists(full):
                    print(f"{name}:{number}: {target}: no such file")
                    broken += 1
                elif anchor and full.endswith(".md") and anchor not in slugs(full):
                    print(f"{name}:{number}: {target}: no heading #{anchor}")
                    broken += 1
    print(f"{count} links in {len(files)} files, {broken} broken")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
