"""The one rule for what a run may write over, checked before any work: a file already at a
target is kept unless it is this same run's (a rerun, which would write it again as it is) or
the user said `--overwrite`; a recorded dataset's folder is never written into by another
command (its files are the dataset's). Every writer's target passes through `check_file` or
`check_not_dataset`, and every file then lands whole through `files.write_atomic`.

A JSON result of pyramid-sim's is told from a user's own file by its keys, so the refusal says
which it is: another run's result, or a file this command did not write.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

from ..errors import ConfigError

OVERWRITE = "--overwrite to replace it"
DATASET_MARKS = ("meta/info.json", "meta/pyramid_sim")  # lerobot's, and our records


def is_dataset(folder: Path) -> bool:
    """Whether `folder` holds a LeRobot dataset (lerobot's metadata, or pyramid-sim's)."""
    return any((folder / mark).exists() for mark in DATASET_MARKS)


def check_not_dataset(folder: Path | None, what: str = "out") -> None:
    """ConfigError if `folder` is a recorded dataset's: a build's or an evaluation's files
    there would be taken for the dataset's (and `record` refuses a folder holding them)."""
    if folder is not None and folder.is_dir() and is_dataset(folder):
        raise ConfigError(
            f"{what}: {str(folder)!r} is a recorded dataset's folder, which only record writes "
            "in; accepted a folder that holds no dataset"
        )


def read_document(path: Path, keys: Iterable[str]) -> dict[str, Any] | None:
    """The JSON object at `path` if it has every one of `keys` (a result of ours), else None."""
    try:
        document = json.loads(path.read_bytes())
    except (OSError, ValueError):
        return None
    if isinstance(document, dict) and all(key in document for key in keys):
        return document
    return None


def check_file(
    path: Path,
    what: str,
    kind: str,
    *,
    overwrite: bool,
    same: Callable[[Path], bool] | None = None,
    ours: Callable[[Path], bool] | None = None,
) -> None:
    """ConfigError, before any work, if `path` holds something this run may not replace:
    accepted are nothing there, this same run's file (`same`), or anything with `overwrite`.
    `kind` names what the run writes there ("build's result"); `ours` tells another run's such
    file from one this command did not write, for the message."""
    if not (path.exists() or path.is_symlink()):
        return
    if path.is_dir():
        raise ConfigError(
            f"{what}: {str(path)!r} is a folder where a {kind} goes; accepted a path that holds "
            "no folder"
        )
    if overwrite or (same is not None and same(path)):
        return
    held = f"another {kind}" if ours is not None and ours(path) else "a file it did not write"
    raise ConfigError(
        f"{what}: {str(path)!r} already holds {held}; accepted a path that holds nothing yet, "
        f"the same run again, or {OVERWRITE}"
    )
