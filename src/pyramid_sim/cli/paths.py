"""What is wrong with a text as an output path, told before anything runs: the OS would
refuse it only midway (a name over NAME_MAX), or take it for something unmeant (an empty path
for the working folder, a folder for a file). `args.output_path` reads every one through here.
And where a `--policy module:factory` is looked for: beside the user, as `python -m` looks.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path


def path_problem(text: str, folder: bool) -> str:
    """What is wrong with `text` as an output path, or "" if nothing is."""
    if not text.strip() or "\0" in text:
        return f"{text!r} is not a path"
    path = Path(text).absolute()
    long_name = _long_name(path)
    if long_name:
        return long_name
    if len(os.fsencode(str(path))) >= _limit(path, "PC_PATH_MAX", 4096):
        return f"{len(os.fsencode(str(path)))} bytes is too long a path"
    if not folder and _is_dir(path):
        return f"{text!r} is a folder"
    return ""


def _long_name(path: Path) -> str:
    """A name in absolute `path` longer than its file system's NAME_MAX, described, or ""."""
    parent = Path(path.anchor)
    limit, parent_exists = _limit(parent, "PC_NAME_MAX", 255), True
    for name in path.parts[1:]:
        size = len(os.fsencode(name))
        if size > limit:
            shown = name if len(name) <= 24 else f"{name[:20]}..."
            return f"a name of {size} bytes ({shown!r}), over the {limit} a name may have"
        if parent_exists:
            parent = parent / name
            parent_exists = _is_dir(parent)
            if parent_exists:
                limit = _limit(parent, "PC_NAME_MAX", limit)
    return ""


def _limit(folder: Path, name: str, fallback: int) -> int:
    """os.pathconf's `name` for `folder`, or `fallback` where the system does not say."""
    try:
        return os.pathconf(folder, name)
    except (OSError, ValueError, AttributeError):
        return fallback


def _is_dir(path: Path) -> bool:
    try:
        return path.is_dir()
    except OSError:
        return False


def policies_from_here() -> None:
    """A `--policy module:factory` found beside the user, as `python -m` finds a module: the
    current folder on the import path."""
    if "" not in sys.path and os.getcwd() not in sys.path:
        sys.path.insert(0, os.getcwd())
