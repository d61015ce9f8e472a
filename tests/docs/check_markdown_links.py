#!/usr/bin/env python3
"""The Markdown pages' own links, as a forge renders them: README.md and docs/*.md.

    check_markdown_links.py SOURCE_DIR

Every relative link of README.md and docs/*.md, [text](target) or ![alt](target) outside code,
must name a file of the repository (relative to the page), and a #fragment must be the anchor a
forge makes of one of the target page's headings (GitHub's rule: lower case, punctuation dropped,
spaces to hyphens, a repeat numbered -1, -2, ...). Sphinx checks the docs pages' links when it
builds the site; this checks them, and the README's, as they read in the repository. Exit status
1, naming each broken link, when one is; 0 otherwise."""
import pathlib
import re
import sys

LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(([^)\s]+)\)")
FENCE = re.compile(r"^(```|~~~)")


def prose(path):
    """(line number, line) of the page outside fenced blocks."""
    fenced = False
    for number, line in enumerate(path.read_text().splitlines(), 1):
        if FENCE.match(line.strip()):
            fenced = not fenced
        elif not fenced:
            yield number, line


def slugs(path):
    """The anchors a forge gives the page's headings (code spans' text included)."""
    seen, found = {}, set()
    for _, line in prose(path):
        m = re.match(r"^#{1,6}\s+(.*?)\s*$", line)
        if not m:
            continue
        slug = re.sub(r"[^\w\- ]", "", m.group(1).lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        found.add(slug if n == 0 else f"{slug}-{n}")
    return found


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    pages = [root / "README.md", *sorted((root / "docs").glob("*.md"))]
    failures, checked = [], 0
    for page in pages:
        for number, line in prose(page):
            for m in LINK.finditer(re.sub(r"`[^`]*`", "", line)):
                target = m.group(1)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("//"):
                    continue  # https:, mailto:
                checked += 1
                path, _, fragment = target.partition("#")
                file = (page.parent / path).resolve() if path else page
                where = f"{page.relative_to(root)}:{number}: ({target})"
                if not file.exists():
                    failures.append(f"{where}: no such file")
                elif fragment and file.suffix == ".md" and fragment not in slugs(file):
                    failures.append(f"{where}: {file.relative_to(root)} has no heading #{fragment}")
    for f in failures:
        print("FAILED  " + f)
    print(f"{checked} relative links in {len(pages)} Markdown pages, {len(failures)} broken")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
