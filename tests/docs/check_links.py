#!/usr/bin/env python3
"""The documentation site's links: every page near the index, no internal link broken.

    check_links.py HTML_DIR [--depth 2]

Crawls the built site (build/docs/html) from index.html, following every internal reference of
each page reached: <a href>, <link href>, <img src>, <script src> that name a file of the site
(not http:, https:, mailto:). Fails, naming the page and the reference, when
  - a reference names a file that does not exist, or
  - a reference to a page carries a #fragment that no id (or <a name>) of that page holds, or
  - a page of the site (every .html file outside _static/, _sources/, _images/) is not reached
    within --depth links of index.html (index.html itself is depth 0).
Exit status 0 when all hold, 1 otherwise (each failure printed)."""
import argparse
import collections
import html.parser
import pathlib
import sys
import urllib.parse

SKIP_DIRS = {"_static", "_sources", "_images", "_downloads"}


class Page(html.parser.HTMLParser):
    """The references and the anchors (id=, <a name=>) of one HTML file."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.refs, self.anchors = [], set()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if a.get("id"):
            self.anchors.add(a["id"])
        if tag == "a" and a.get("name"):
            self.anchors.add(a["name"])
        for key in ("href", "src"):
            if a.get(key) is not None and tag in ("a", "link", "img", "script"):
                self.refs.append((tag, a[key]))


def parse(path, cache):
    if path not in cache:
        p = Page()
        p.feed(path.read_text(errors="replace"))
        cache[path] = p
    return cache[path]


def internal_target(page_path, ref, root):
    """(file, fragment) a reference names inside the site, or None for an external one."""
    parts = urllib.parse.urlsplit(ref)
    if parts.scheme or parts.netloc or ref.startswith("//"):
        return None  # http:, https:, mailto:, data:, javascript:
    path = urllib.parse.unquote(parts.path)
    target = page_path if not path else (page_path.parent / path)
    target = pathlib.Path(*[p for p in target.parts])  # keep as given; resolve below
    try:
        target = target.resolve()
    except OSError:
        pass
    if target.is_dir():
        target = target / "index.html"
    return target, urllib.parse.unquote(parts.fragment)


def site_pages(root):
    return sorted(p.resolve() for p in root.rglob("*.html")
                  if not SKIP_DIRS.intersection(p.relative_to(root).parts[:-1]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("html_dir")
    ap.add_argument("--depth", type=int, default=2)
    args = ap.parse_args()
    root = pathlib.Path(args.html_dir).resolve()
    index = root / "index.html"
    if not index.is_file():
        print(f"FAILED  no {index}: build the site first (cmake --build build --target docs)")
        return 1
    failures, cache = [], {}
    depth = {index: 0}
    queue = collections.deque([index])
    checked = 0
    while queue:
        page = queue.popleft()
        for tag, ref in parse(page, cache).refs:
            t = internal_target(page, ref, root)
            if t is None:
                continue
            target, fragment = t
            checked += 1
            where = f"{page.relative_to(root)}: <{tag}> {ref!r}"
            if root not in target.parents and target != root:
                failures.append(f"{where} leaves the site ({target})")
                continue
            if not target.is_file():
                failures.append(f"{where} names a missing file")
                continue
            if target.suffix != ".html":
                continue
            if fragment and fragment not in parse(target, cache).anchors:
                failures.append(f"{where}: {target.relative_to(root)} has no anchor #{fragment}")
            if tag == "a" and target not in depth:
                depth[target] = depth[page] + 1
                if depth[target] <= args.depth:
                    queue.append(target)
    pages = site_pages(root)
    for p in pages:
        d = depth.get(p)
        if d is None or d > args.depth:
            how = "not reached" if d is None else f"{d} links away"
            failures.append(f"{p.relative_to(root)}: {how} from index.html (at most {args.depth})")
    for f in failures:
        print("FAILED  " + f)
    print(f"{len(pages)} pages, {checked} internal references checked from the pages within "
          f"{args.depth} links of index.html, {len(failures)} problems")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
