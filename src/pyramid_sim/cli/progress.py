"""Progress of a long job (a build, a sweep, `record`'s and `evaluate`'s episodes) on stderr:
tqdm bars on a terminal, with the units done and the time left; elsewhere (a CI log, a file) a
few plain lines, one at each tenth of the work, each with the time left at this run's pace, as
a bar's redraws there become hundreds of lines.

Only what is known is shown: the film's frame count has no total until the build ends (its
simulated end is not known before), so it is counted without one and given its total then,
never an estimate it could pass. Work done before this run (a resumed sweep's rows) is the
starting count, not progress, so the rate counts only what this run did.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from types import TracebackType
from typing import Any, TextIO

# A terminal that reports no size (a pseudo-terminal nobody sized: `script`, an editor's
# shell, some CI runners) reads as 0 by 0, and tqdm then draws nothing at all: this size.
FALLBACK_SIZE = (100, 20)  # columns, rows
STEPS = 10  # plain lines for a whole run, at most (plus one for work done before, one at a stop)


class Progress:
    """Counts `unit`s of work towards `total`, with an optional second count (`count_unit`,
    e.g. frames) that has no total of its own."""

    def __init__(
        self,
        desc: str,
        total: int,
        unit: str,
        *,
        count_unit: str | None = None,
        stream: TextIO | None = None,
        quiet: bool = False,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.desc, self.total, self.unit, self.count_unit = desc, total, unit, count_unit
        self.stream = sys.stderr if stream is None else stream
        self.quiet, self.clock = quiet, clock
        self.tty = not quiet and bool(getattr(self.stream, "isatty", lambda: False)())
        self.n = self.initial = self.counted = 0
        self.started: float | None = None
        self._step = 0  # tenths of the work reported in plain lines so far
        self._bars: list[Any] = []

    def start(self, done: int = 0, *, total: int | None = None) -> None:
        """Begin timing, `done` units already finished before this run (reported, not rated);
        `total` when it was not known at the start (a build's bricks, once planned)."""
        if self.started is not None:
            return
        if total is not None:
            self.total = total
        self.n = self.initial = done
        self.started = self.clock()
        if self.quiet:
            return
        if self.tty:
            from tqdm import tqdm

            sized = _sized(self.stream)  # else tqdm draws nothing
            width, height = (None, None) if sized else FALLBACK_SIZE
            self._bars.append(
                tqdm(
                    total=self.total,
                    initial=done,
                    unit=self.unit,
                    desc=self.desc,
                    file=self.stream,
                    ncols=width,
                    nrows=height,
                )
            )
            if self.count_unit is not None:
                # no total, so tqdm writes the count and unit run together: spaced here
                self._bars.append(
                    tqdm(
                        unit=f" {self.count_unit}",
                        desc=f"{self.count_unit}s",
                        position=1,
                        file=self.stream,
                        ncols=width,
                        nrows=height,
                    )
                )
            return
        self._step = self._tenths(done)
        if done:
            self._line(f"{done}/{self.total} {self.unit}s done before")

    def advance(self, by: int = 1) -> None:
        """`by` more units finished."""
        self.advance_to(self.n + by)

    def advance_to(self, n: int) -> None:
        """`n` units finished so far."""
        self.start()
        if n <= self.n:
            return
        by, self.n = n - self.n, n
        if self.tty:
            self._bars[0].update(by)
        elif not self.quiet and self._tenths(n) > self._step:
            self._step = self._tenths(n)
            self._line(self._status())

    def count(self, by: int = 1) -> None:
        """`by` more of the second count (a frame filmed)."""
        self.counted += by
        if self.tty and len(self._bars) > 1:
            self._bars[1].update(by)

    def recording_hooks(self) -> tuple[Callable[[int, int], None], Callable[[int], None]]:
        """`record`'s `on_frame` and `on_episode` reported here: episodes on the bar, frames on
        the second count (with workers, an episode's frames all at once as it ends)."""
        filmed: dict[int, int] = {}

        def on_frame(episode: int, frames: int) -> None:
            self.count(frames - filmed.get(episode, 0))
            filmed[episode] = frames

        def on_episode(episodes: int) -> None:
            self.start(episodes)  # the first call: those a resumed run found done
            self.advance_to(episodes)

        return on_frame, on_episode

    def close(self, stopped: bool = False) -> None:
        """End the report; the second count gets its total, now known. A run that ended
        short of its total says where it ended, unless it was `stopped` (an error is said
        elsewhere)."""
        if self.tty:
            if len(self._bars) > 1:
                self._bars[1].total = self._bars[1].n
                self._bars[1].refresh()
            for bar in reversed(self._bars):
                bar.close()
            self._bars = []
        elif not self.quiet and self.started is not None and not stopped:
            if self.n < self.total:
                self._line(self._status())

    def __enter__(self) -> Progress:
        return self

    def __exit__(
        self, kind: type[BaseException] | None, err: BaseException | None, tb: TracebackType | None
    ) -> None:
        self.close(stopped=kind is not None)

    def _tenths(self, n: int) -> int:
        return n * STEPS // self.total if self.total else STEPS

    def _status(self) -> str:
        elapsed = self.clock() - (self.started or 0.0)
        done_now = self.n - self.initial
        parts = [
            f"{self.n}/{self.total} {self.unit}s "
            f"({100 * self.n // max(self.total, 1)}%) in {duration(elapsed)}"
        ]
        if done_now:
            parts.append(f"{elapsed / done_now:.1f} s/{self.unit}")
            if self.n < self.total:  # at this run's pace so far, as a bar's estimate is
                parts.append(f"about {duration(elapsed / done_now * (self.total - self.n))} left")
        if self.count_unit is not None:
            parts.append(f"{self.counted} {self.count_unit}s")
        return ", ".join(parts)

    def _line(self, text: str) -> None:
        print(f"{self.desc}: {text}", file=self.stream, flush=True)


def _sized(stream: TextIO) -> bool:
    """Whether the terminal reports its size (a stream that is no file: tqdm's own default)."""
    try:
        size = os.get_terminal_size(stream.fileno())
    except (AttributeError, OSError, ValueError):
        return True
    return size.columns > 0 and size.lines > 0


def duration(seconds: float) -> str:
    """`42 s`, `4 min 17 s`, `1 h 02 min`: a span for a log line."""
    whole = int(round(seconds))
    if whole < 60:
        return f"{whole} s"
    if whole < 3600:
        return f"{whole // 60} min {whole % 60} s"
    return f"{whole // 3600} h {whole % 3600 // 60:02d} min"
