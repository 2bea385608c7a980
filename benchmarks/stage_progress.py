"""Progress of baseline.py's long stages on stderr (recording, training, scoring): the house's
bar (pyramid_sim.cli.progress) with what is done and the time left on a terminal, nothing in a
log, where a row's run usually goes. lerobot-train runs as a child writing its own log, so a
training's steps are read off that log while it runs."""

from __future__ import annotations

import re
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from pyramid_sim.cli.progress import Progress

POLL_S = 1.0  # how often a running training's log is read
TAIL = 4096  # bytes read off the log's end: one redraw of lerobot's bar is about 70
# lerobot-train's own bar, redrawn with a carriage return ("Training:  95%|█████████▌|
# 3800/4000 [38:43<01:32,  2.15step/s]"), and its line at each checkpoint ("Checkpoint policy
# after step 4000"); its "step:4K" lines are rounded, so not read
STEP = re.compile(r"Training:\s*\d+%\|[^|]*\|\s*(\d+)/\d+|Checkpoint policy after step (\d+)")


def stage(desc: str, total: int, unit: str, count_unit: str | None = None) -> Progress:
    """A stage's progress towards `total` `unit`s: a bar when stderr is a terminal, quiet
    otherwise."""
    stream = sys.stderr
    tty = bool(getattr(stream, "isatty", lambda: False)())
    return Progress(desc, total, unit, count_unit=count_unit, stream=stream, quiet=not tty)


def last_step(text: str) -> int | None:
    """The last training step lerobot-train's log `text` shows done, or None if none yet."""
    found = None
    for match in STEP.finditer(text):
        found = int(match.group(1) or match.group(2))
    return found


@contextmanager
def following(log: Path, progress: Progress, every: float | None = None) -> Iterator[None]:
    """`progress` moved to the step `log` shows, every `every` seconds (POLL_S) while the
    block runs and once more when it ends well; a quiet `progress` reads nothing."""
    every = POLL_S if every is None else every
    if progress.quiet:
        yield
        return
    stop = threading.Event()

    def poll() -> None:
        while not stop.wait(every):
            _advance(log, progress)

    reader = threading.Thread(target=poll, name="training-log", daemon=True)
    reader.start()
    try:
        yield
    finally:
        stop.set()
        reader.join()
    _advance(log, progress)


def _advance(log: Path, progress: Progress) -> None:
    try:
        with open(log, "rb") as text:
            size = text.seek(0, 2)
            text.seek(max(0, size - TAIL))
            tail = text.read().decode("utf-8", "replace")
    except OSError:  # not there yet
        return
    step = last_step(tail)
    if step is not None:
        progress.advance_to(min(step, progress.total))
