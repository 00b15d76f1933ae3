#!/usr/bin/env python3
"""Checks the links of the built user guide (docs/guide/book) and of README.md.

mdBook builds a guide with a broken link, a missing picture or an {{#include}} of a missing
file and exits 0; this finds them. Every relative href and src in the built HTML must name a
file or folder that exists, a #fragment must name an element id of the page it points into,
and no mdBook directive may be left in a page. Every relative link and picture of README.md
must name a path in the repository, and a #fragment into a Markdown file one of its
headings. Links with a scheme (http:, https:, mailto:, ...) are not checked. Exits 1 naming
each broken link, its file and its target. Python's standard library only.

    python3 scripts/check-guide.py        # after `mdbook build docs/guide`
"""

from __future__ import annotations

import re
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

ROOT = Path(__file__).resolve().parent.parent
BOOK = ROOT / "docs" / "guide" / "book"
README = ROOT / "README.md"


class Page(HTMLParser):
    """One HTML page's element ids, its links (href, src) and its <base href>, if any."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.ids: set[str] = set()
        self.links: list[str] = []
        self.base: str | None = None

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        for name, value in attrs:
            if value is None:
                continue
            if name == "id" or (tag == "a" and name == "name"):
                self.ids.add(value)
            elif tag == "base" and name == "href":
                self.base = value
            elif name in ("href", "src"):
                self.links.append(value)


def is_external(link: str) -> bool:
    """A link with a scheme (http:, mailto:, data:, javascript:) or to another host."""
    return link.startswith("//") or re.match(r"[A-Za-z][A-Za-z0-9+.-]*:", link) is not None


def github_slug(heading: str) -> str:
    """The id GitHub (and mdBook) gives a Markdown heading: lower case, punctuation dropped,
    spaces as hyphens."""
    text = re.sub(r"[`*_]|<[^>]*>", "", heading).strip().lower()
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def markdown_ids(path: Path) -> set[str]:
    """The heading ids of a Markdown file, repeated headings numbered -1, -2, ... as GitHub
    does; headings inside fenced code are no headings."""
    ids: set[str] = set()
    fenced = False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced and (m := re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)):
            slug = github_slug(m.group(1))
            n, candidate = 0, slug
            while candidate in ids:
                n += 1
                candidate = f"{slug}-{n}"
            ids.add(candidate)
    return ids


def shown(path: Path) -> str:
    """A path as the messages show it: from the repository's root where it lies inside."""
    return str(path.relative_to(ROOT)) if path.is_relative_to(ROOT) else str(path)


def check_book() -> list[str]:
    """Every relative link of every built page, with the pages' ids read once each."""
    if not BOOK.is_dir():
        return [f"{BOOK.relative_to(ROOT)}: missing (run `mdbook build docs/guide` first)"]
    pages: dict[Path, Page] = {}
    errors = []
    for html in sorted(BOOK.rglob("*.html")):
        text = html.read_text(encoding="utf-8")
        page = Page()
        page.feed(text)
        pages[html.resolve()] = page
        # An {{#include}} whose file mdBook cannot read stays in the page as written, with
        # only a logged error and exit status 0.
        if "{{#" in text:
            errors.append(f"{html.relative_to(ROOT)}: an mdBook directive left unexpanded "
                          "(an {{#include}} of a missing file?)")
    for html, page in pages.items():
        # A <base href="/"> (mdBook's 404 page) makes links relative to the book's root.
        base = html.parent
        if page.base is not None and not is_external(page.base):
            start = BOOK if page.base.startswith("/") else html.parent
            base = (start / page.base.lstrip("/")).resolve()
        for link in page.links:
            if not link or is_external(link):
                continue
            parts = urlsplit(link)
            path = unquote(parts.path)
            if path.startswith("/"):
                target = (BOOK / path.lstrip("/")).resolve()
            elif path:
                target = (base / path).resolve()
            else:
                target = html
            where = f"{html.relative_to(ROOT)}: {link}"
            if not target.exists():
                errors.append(f"{where}: no file {shown(target)}")
            elif parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else set()
                if unquote(parts.fragment) not in ids:
                    errors.append(f"{where}: no id {parts.fragment!r} in {shown(target)}")
    return errors


def check_readme() -> list[str]:
    """README.md's relative links and pictures, outside fenced code, against the repository."""
    errors = []
    fenced = False
    for number, line in enumerate(README.read_text(encoding="utf-8").splitlines(), 1):
        if line.startswith("```"):
            fenced = not fenced
            continue
        if fenced:
            continue
        line = re.sub(r"`[^`]*`", "", line)  # code spans hold commands, not links
        links = re.findall(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)", line)
        links += re.findall(r"""(?:src|href)=["']([^"']+)["']""", line)
        for link in links:
            if is_external(link):
                continue
            parts = urlsplit(link)
            target = (README.parent / unquote(parts.path)).resolve() if parts.path else README
            where = f"README.md:{number}: {link}"
            if not target.exists():
                errors.append(f"{where}: no file {parts.path}")
            elif parts.fragment and target.suffix == ".md":
                if parts.fragment not in markdown_ids(target):
                    name = parts.path or "README.md"
                    errors.append(f"{where}: no heading {parts.fragment!r} in {name}")
    return errors


def main() -> int:
    errors = check_book() + check_readme()
    for error in errors:
        print(f"broken link: {error}", file=sys.stderr)
    if errors:
        print(f"check-guide: {len(errors)} broken link(s)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
