#!/usr/bin/env python3
"""The map of the code, docs/code_map.md, made from the modules' own docstrings.

    python3 scripts/design_map.py [--check]

One entry a module under src/pyramid_sim: its path and the first sentence of its docstring,
whole, grouped by sub-package, each group headed by its `__init__.py`'s first sentence. The
map goes between the marker comments in docs/code_map.md (docs/design.md links it);
`--check` changes nothing and exits 1 if the map there is not the one the code makes (as
tests/test_design_map.py does). Read with `ast` only: nothing of pyramid_sim is imported.
"""

from __future__ import annotations

import argparse
import ast
import re
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src" / "pyramid_sim"
MAP_PAGE = ROOT / "docs" / "code_map.md"
START = "<!-- map:start: made by scripts/design_map.py from the docstrings; edit those -->"
END = "<!-- map:end -->"
WIDTH = 100
NO_DOCSTRING = "(no docstring)"


def summary(path: Path) -> str | None:
    """The first sentence of the module's docstring, whole (its first paragraph's lines joined
    up to the first full stop, question or exclamation mark that ends a sentence). None for
    a module without a docstring."""
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8")))
    if not doc or not doc.strip():
        return None
    paragraph = " ".join(line.strip() for line in doc.strip().split("\n\n")[0].splitlines())
    ended = re.search(r"[.?!](?=\s|$)", paragraph)
    return paragraph[: ended.end()] if ended else paragraph


def modules(src: Path = SRC) -> dict[str, list[Path]]:
    """The package's modules by sub-package ("" for the top level), each sorted by path."""
    groups: dict[str, list[Path]] = {}
    for path in sorted(src.rglob("*.py")):
        if "__pycache__" in path.parts:
            continue
        package = path.parent.relative_to(src).as_posix()
        groups.setdefault("" if package == "." else package, []).append(path)
    return dict(sorted(groups.items()))


def undocumented(src: Path = SRC) -> list[str]:
    """The modules without a docstring, by path under src/pyramid_sim."""
    return [
        p.relative_to(src).as_posix()
        for paths in modules(src).values()
        for p in paths
        if summary(p) is None
    ]


def _fill(text: str, indent: str = "") -> str:
    return textwrap.fill(
        text, WIDTH, subsequent_indent=indent, break_long_words=False, break_on_hyphens=False
    )


def render(src: Path = SRC) -> str:
    """The map, as Markdown: a paragraph naming each sub-package and a list of its modules (a
    package of rooms alone, of its rooms)."""
    blocks = []
    grouped = modules(src)
    for package, paths in grouped.items():
        init = src / package / "__init__.py"
        if package:
            heading = f"`{package}/`: {summary(init) or NO_DOCSTRING}"
        else:
            heading = "The top level, `src/pyramid_sim/`:"
        items = [
            _fill(f"- `{p.relative_to(src).as_posix()}`: {summary(p) or NO_DOCSTRING}", "  ")
            for p in paths
            if package == "" or p != init
        ]
        if not items:  # rooms only: name them, each described under its own heading
            rooms = [
                f"`{p}/`"
                for p in grouped
                if p.startswith(f"{package}/") and p.count("/") == package.count("/") + 1
            ]
            items = [_fill(f"- its rooms: {', '.join(rooms)}", "  ")]
        blocks.append(_fill(heading) + "\n\n" + "\n".join(items))
    return "\n\n".join(blocks) + "\n"


def current(text: str) -> str:
    """The map between the markers of `text` (ValueError without both markers, in order)."""
    start, end = text.index(START), text.index(END)
    if end < start:
        raise ValueError(f"{END} comes before the start marker")
    return text[start + len(START) : end].strip("\n") + "\n"


def updated(text: str, src: Path = SRC) -> str:
    """`text` with the map between its markers made afresh."""
    start, end = text.index(START), text.index(END)
    return text[: start + len(START)] + "\n\n" + render(src) + "\n" + text[end:]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="change nothing; exit 1 if stale")
    args = parser.parse_args(argv)
    for path in undocumented():
        print(f"design_map: src/pyramid_sim/{path} has no docstring", file=sys.stderr)
    text = MAP_PAGE.read_text(encoding="utf-8")
    fresh = updated(text)
    if args.check:
        if fresh != text:
            print("design_map: the map in docs/code_map.md is stale; run it", file=sys.stderr)
            return 1
        return 0
    if fresh != text:
        MAP_PAGE.write_text(fresh, encoding="utf-8")
        print("design_map: docs/code_map.md made afresh", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
