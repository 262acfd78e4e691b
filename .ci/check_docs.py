#!/usr/bin/env python3
"""Checks the links between the project's documentation pages. Exit 1 when any is broken.

The pages: README.md, docs/*.md, engine/PHYSICS.md and every README.md below assets/. In each,
every relative markdown link ([text](target), ![alt](target) and [name]: target definitions;
not inside code spans or fenced code blocks) must name a file or folder that exists, relative
to the page, and a '#anchor' must be a heading (or an id="..."/name="..." anchor) of the
markdown file it names, or of the page itself when no file is named. Anchors follow GitHub's
rule: the heading's text without its markup, lower case, every character that is not a letter,
digit, space, '-' or '_' removed, each space turned into '-'; a repeated heading gets '-1',
'-2', ... Links with a scheme (https:, mailto:) are not followed.

Every docs/*.md page must also be reachable from README.md by following links between pages.

One line per problem, FILE:LINE: ..., then exit 1; exit 0 and a summary line when all is well.
Usage: check_docs.py [--root DIR] (default: the repository holding this script).
"""
import argparse
import collections
import pathlib
import re
import sys
import urllib.parse

FENCE = re.compile(r"^\s{0,3}(`{3,}|~{3,})")
# A code span may run over lines of one paragraph, never past a blank line; so may a link's text.
CODE_SPAN = re.compile(r"(`+)((?:(?!\n[ \t]*\n).)+?)\1", re.DOTALL)
INLINE_LINK = re.compile(
    r"!?\[(?:(?!\n[ \t]*\n)[^\[\]]|\[[^\[\]\n]*\])*\]"  # [text], one level of [] inside
    r"\(\s*(<[^>]*>|[^()\s]*(?:\([^()\s]*\)[^()\s]*)*)"  # (target, balanced parentheses
    r"(?:\s+\"[^\"]*\")?\s*\)")  # and an optional "title")
DEFINITION = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)(?:\s+#+)?\s*$")
HTML_ANCHOR = re.compile(r"<a\s[^>]*\b(?:name|id)\s*=\s*\"([^\"]+)\"", re.IGNORECASE)
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")


def pages(root: pathlib.Path) -> list[pathlib.Path]:
    """The pages whose links are checked, as paths under root, in a stable order."""
    found = [root / "README.md", root / "engine" / "PHYSICS.md"]
    found += sorted((root / "docs").glob("*.md"))
    found += sorted((root / "assets").glob("**/README.md"))
    return [page for page in found if page.is_file()]


def outside_fences(text: str):
    """(line number, line) of the lines outside fenced code blocks."""
    fence = None
    for number, line in enumerate(text.splitlines(), start=1):
        match = FENCE.match(line)
        if fence is None:
            if match:
                fence = match.group(1)
            else:
                yield number, line
        elif line.strip().startswith(fence) and set(line.strip()) <= {fence[0]}:
            fence = None


def prose(text: str) -> str:
    """The page with its fenced code blocks and code spans blanked out (line breaks kept, so
    offsets still give line numbers)."""
    lines = text.splitlines()
    kept = dict(outside_fences(text))
    blanked = "\n".join(kept.get(number, "") for number in range(1, len(lines) + 1))
    return CODE_SPAN.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), blanked)


def heading_text(raw: str) -> str:
    """A heading's text as GitHub renders it: links by their text, code and emphasis unmarked."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", raw)
    text = re.sub(r"<[^>]+>", "", text)
    return text.replace("`", "")


def slug(text: str) -> str:
    """GitHub's anchor for a heading's text (before duplicates are numbered)."""
    kept = "".join(c for c in heading_text(text).lower() if c.isalnum() or c in " -_")
    return kept.replace(" ", "-")


def anchors(page: pathlib.Path, cache: dict) -> set:
    """Every anchor a markdown page defines: its headings' slugs (numbered when repeated) and
    its HTML name/id anchors."""
    if page not in cache:
        seen = collections.Counter()
        found = set()
        for _, line in outside_fences(page.read_text(encoding="utf-8")):
            found.update(HTML_ANCHOR.findall(line))
            heading = HEADING.match(line)
            if heading:
                base = slug(heading.group(2))
                found.add(base if seen[base] == 0 else f"{base}-{seen[base]}")
                seen[base] += 1
        cache[page] = found
    return cache[page]


def links(page: pathlib.Path):
    """(line number, target) of every link on the page that is not code; a link whose text runs
    over lines is numbered by the line of its target."""
    text = prose(page.read_text(encoding="utf-8"))
    for match in INLINE_LINK.finditer(text):
        yield text.count("\n", 0, match.start(1)) + 1, match.group(1).strip("<>")
    for number, line in enumerate(text.split("\n"), start=1):
        definition = DEFINITION.match(line)
        if definition:
            yield number, definition.group(1).strip("<>")


def resolve(page: pathlib.Path, target: str, root: pathlib.Path, cache: dict):
    """The file a relative link leads to (None for an external link), and whether it resolves."""
    if SCHEME.match(target) or target.startswith("//"):
        return None, True
    path_part, _, anchor = target.partition("#")
    path_part = urllib.parse.unquote(path_part)
    destination = (page.parent / path_part).resolve() if path_part else page.resolve()
    if path_part.startswith("/"):
        destination = (root / path_part.lstrip("/")).resolve()
    if not destination.exists():
        return destination, False
    if anchor:
        if destination.suffix.lower() != ".md" or not destination.is_file():
            return destination, False
        if urllib.parse.unquote(anchor).lower() not in anchors(destination, cache):
            return destination, False
    return destination, True


def check(root: pathlib.Path) -> tuple[list[str], str]:
    """The problems found under root, one line each, and what was checked."""
    root = root.resolve()
    problems = []
    cache = {}
    graph = {}
    checked = pages(root)
    count = 0
    for page in checked:
        name = page.relative_to(root).as_posix()
        graph[page.resolve()] = set()
        for number, target in links(page):
            count += 1
            destination, ok = resolve(page, target, root, cache)
            if not ok:
                problems.append(f"{name}:{number}: link '{target}' points nowhere")
            elif destination is not None and destination.suffix.lower() == ".md":
                graph[page.resolve()].add(destination)
    reached = set()
    readme = (root / "README.md").resolve()
    queue = collections.deque([readme] if readme in graph else [])
    while queue:
        current = queue.popleft()
        if current in reached:
            continue
        reached.add(current)
        queue.extend(graph.get(current, ()))
    for page in sorted((root / "docs").glob("*.md")):
        if page.resolve() not in reached:
            name = page.relative_to(root).as_posix()
            problems.append(f"{name}:1: page not reachable from README.md by following links")
    return problems, f"{count} links in {len(checked)} pages"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=pathlib.Path,
                        default=pathlib.Path(__file__).resolve().parent.parent,
                        help="the repository to check (default: the one holding this script)")
    args = parser.parse_args()
    if not (args.root / "README.md").is_file():
        print(f"{args.root}: no README.md", file=sys.stderr)
        return 1
    problems, summary = check(args.root)
    for problem in problems:
        print(problem)
    if problems:
        print(f"documentation links: {len(problems)} problems ({summary})")
        return 1
    print(f"documentation links: {summary}; all resolve, every docs page is reachable")
    return 0


if __name__ == "__main__":
    sys.exit(main())
