"""Writing files whole or not at all: every writer of pyramid_sim goes through here.

A file is written under a temporary name beside its destination and renamed into place when
complete, so an interrupted run never leaves a half-written result, video, still or plot.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from ..errors import ConfigError


def temporary_beside(path: Path, suffix: str | None = None) -> Path:
    """A new empty file next to `path` (same folder, so the final rename is atomic), ending in
    `path`'s suffix (writers that read the format from the name) or in `suffix` (".part" in a
    dataset, so no reader's glob sees it)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    ending = path.suffix if suffix is None else suffix
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=ending, dir=path.parent)
    os.close(fd)
    os.chmod(tmp, 0o644)  # mkstemp makes it private; the finished file is an ordinary one
    return Path(tmp)


@contextmanager
def atomic_path(path: Path, suffix: str | None = None) -> Iterator[Path]:
    """Yield a temporary path to write (named as `temporary_beside` names it); on success it
    becomes `path`, on any error it goes."""
    tmp = temporary_beside(path, suffix)
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


@contextmanager
def atomic_dir(path: Path) -> Iterator[Path]:
    """Yield a new empty folder beside `path` to fill; on success it takes the place of `path`
    (an earlier folder there is removed), on any error it goes and an earlier one stays: a
    folder of files is never seen half written."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{path.name}.", dir=path.parent))
    os.chmod(tmp, 0o755)  # mkdtemp makes it private; the finished folder is an ordinary one
    aside: Path | None = None
    try:
        yield tmp
        if path.exists():
            aside = Path(tempfile.mkdtemp(prefix=f".{path.name}.old.", dir=path.parent))
            os.replace(path, aside / path.name)
        try:
            os.replace(tmp, path)
        except BaseException:
            if aside is not None:
                os.replace(aside / path.name, path)
            raise
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    finally:
        if aside is not None:
            shutil.rmtree(aside, ignore_errors=True)


def write_atomic(path: Path, write: Callable[[Path], object], suffix: str | None = None) -> None:
    """Call `write(tmp)` and move the finished file to `path`."""
    with atomic_path(path, suffix) as tmp:
        write(tmp)


def move_into_place(source: Path, target: Path) -> None:
    """A finished file (written beside `target`, or in a staging folder on the same disk)
    renamed to `target` in one step."""
    target.parent.mkdir(parents=True, exist_ok=True)
    os.replace(source, target)


def write_json_atomic(path: Path, document: dict[str, Any]) -> None:
    """`document` as indented strict JSON, written atomically."""
    text = json.dumps(document, indent=2, allow_nan=False) + "\n"
    write_atomic(path, lambda tmp: tmp.write_text(text))


def check_writable_dir(path: Path, what: str = "out") -> None:
    """ConfigError unless `path` is, or can be made, a writable folder (nothing is created): a
    link to nothing cannot be made one (the OS would say only "File exists")."""
    probe = Path(path)
    while not probe.exists():
        if probe.is_symlink():
            raise ConfigError(
                f"{what}: {str(probe)!r} is a link to {os.readlink(probe)!r}, which does not "
                "exist; accepted a folder, a path where one can be made, or a link to a folder"
            )
        probe = probe.parent
    if not probe.is_dir():
        raise ConfigError(
            f"{what}: {str(probe)!r} is not a folder; accepted a folder, or a path where one "
            "can be made"
        )
    try:
        with tempfile.TemporaryFile(dir=probe):
            pass
    except OSError as err:
        raise ConfigError(
            f"{what}: {str(probe)!r} is not writable ({err.strerror}); accepted a folder this "
            "user may write in"
        ) from None


@contextmanager
def removed_if_failed(folders: list[Path]) -> Iterator[None]:
    """Folders that do not exist yet and are made inside the block are removed again, if
    still empty, when the block fails or is interrupted: a refused or stopped run leaves no
    empty folders behind."""
    new: list[Path] = []
    for folder in folders:
        folder = folder.resolve()
        while not folder.exists() and folder not in new:
            new.append(folder)
            folder = folder.parent
    try:
        yield
    except BaseException:
        for folder in sorted(new, key=lambda f: len(f.parts), reverse=True):
            try:
                folder.rmdir()  # only if empty
            except OSError:
                pass
        raise
