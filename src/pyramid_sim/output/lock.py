"""One pyramid-sim run at a time in a folder: two builds or sweeps writing one `--out` would
mix their files (a result.json from one run beside the other's MP4, duplicate sweep.csv rows).

A run holds each folder it writes through `flock` on a lock file inside it. The kernel lets go
of the lock when its holder ends in any way, so a run killed outright (SIGKILL, a crash) leaves
at most a stale file, never a lock that blocks. The holder removes the file when it ends; a
run that opened the file just before that checks, once locked, that the path still names the
file it locked, and tries afresh if not.
"""

from __future__ import annotations

import fcntl
import os
import time
from collections.abc import Iterable, Iterator
from contextlib import ExitStack, contextmanager
from pathlib import Path

from ..errors import ConfigError

LOCK_NAME = ".pyramid-sim.lock"


class FolderBusy(ConfigError):
    """Another pyramid-sim run holds the folder: a refusal before anything is written."""


@contextmanager
def holding(folders: Iterable[tuple[Path, str]]) -> Iterator[None]:
    """Hold each (folder, what) for the block, making the folder if missing; FolderBusy naming
    `what`, the folder and the holder's pid if another run holds one. Folders are taken in one
    order and none is waited for, so two runs cannot deadlock."""
    chosen: dict[Path, tuple[Path, str]] = {}
    for folder, what in folders:
        chosen.setdefault(folder.resolve(), (folder, what))
    with ExitStack() as stack:
        for resolved in sorted(chosen):
            stack.enter_context(folder_lock(*chosen[resolved]))
        yield


@contextmanager
def folder_lock(folder: Path, what: str = "out") -> Iterator[Path]:
    """Hold `folder` (made if missing) for the block; yields the lock file's path, which is
    removed again when the block ends, however it ends."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / LOCK_NAME
    fd = _acquire(path, what)
    try:
        yield path
    finally:
        try:
            path.unlink()  # while still locked: a waiter that opened it will see it gone
        except FileNotFoundError:
            pass
        os.close(fd)


def _acquire(path: Path, what: str) -> int:
    """An open descriptor of `path` holding its lock, with this process's pid written in."""
    while True:
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = _holder(fd)
            os.close(fd)
            raise FolderBusy(
                f"{what}: {str(path.parent)!r} is held by another pyramid-sim run ({holder}); "
                "accepted a folder no other run holds: wait for that one to end or choose "
                "another"
            ) from None
        except BaseException:
            os.close(fd)
            raise
        if _names(path, fd):
            os.ftruncate(fd, 0)
            os.write(fd, f"{os.getpid()}\n".encode())
            return fd
        os.close(fd)  # its holder removed it between our open and our lock: try afresh


def _names(path: Path, fd: int) -> bool:
    """Whether `path` still names the file open as `fd`."""
    try:
        on_disk = os.stat(path)
    except FileNotFoundError:
        return False
    held = os.fstat(fd)
    return (on_disk.st_dev, on_disk.st_ino) == (held.st_dev, held.st_ino)


def _holder(fd: int, wait: float = 0.5) -> str:
    """`pid N` of the run holding the lock; it writes its pid just after locking, so an empty
    file is read again for up to `wait` seconds."""
    deadline = time.monotonic() + wait
    while True:
        text = os.pread(fd, 32, 0).decode(errors="replace").strip()
        if text.isdigit():
            return f"pid {text}"
        if time.monotonic() >= deadline:
            return "pid unknown"
        time.sleep(0.02)
