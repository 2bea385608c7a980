"""What a run writes, checked and held before it runs: the folder it writes into, a film's
and a still's paths, each refused in one line where it cannot be written, and every folder
held against any other run while this one writes (one rule for every command that writes)."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from ..config import VideoConfig
from ..errors import ConfigError
from ..options import path_argument
from .claims import check_not_dataset
from .files import check_writable_dir, removed_if_failed
from .lock import holding

Films = dict[str, tuple[VideoConfig, Path]]  # by suffix: .mp4, .png


def out_folder(out: Any) -> Path | None:
    """`out` as a folder's path, checked writable before anything runs, or None."""
    folder = path_argument(out, "out", "a folder's path")
    if folder is not None:
        check_writable_dir(folder)
    return folder


def results_folder(out: Any) -> Path | None:
    """`out` as `out_folder` takes it, and refused if a recorded dataset is there: a build's
    or an evaluation's files would be taken for the dataset's."""
    folder = out_folder(out)
    check_not_dataset(folder)
    return folder


def films(vc: VideoConfig, video: Any, snapshot: Any) -> Films:
    """The film and the still asked for, by suffix; ConfigError for what is not a path, or a
    path without its suffix."""
    found = {}
    for suffix, given in ((".mp4", video), (".png", snapshot)):
        what = f"{suffix[1:]} path"
        path = path_argument(given, what, f"a file's path ending in {suffix}")
        if path is not None:
            if path.suffix.lower() != suffix:
                raise ConfigError(f"{what}: {str(path)!r} must end in {suffix}")
            found[suffix] = (vc, path)
    return found


def build_folders(out: Path | None, films: Films) -> list[tuple[Path, str]]:
    """Each folder a build writes, as it is named in messages; ConfigError for one that
    cannot be written (checked before any physics, and nothing is made)."""
    folders = [(out, "out")] if out is not None else []
    folders += [(path.parent, f"{suffix[1:]} path") for suffix, (_, path) in films.items()]
    for folder, what in folders:
        check_writable_dir(folder, what)
        check_not_dataset(folder, what)
    return folders


@contextmanager
def held(folders: list[tuple[Path, str]]) -> Iterator[None]:
    """The folders a run writes, held against any other run while it runs, and removed again
    if it made them and fails."""
    with removed_if_failed([folder for folder, _ in folders]), holding(folders):
        yield
