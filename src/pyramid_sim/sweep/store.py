"""`sweep.csv`: one row per finished run, appended as each finishes, safe to resume.

A row is written with one `write` on a file opened for appending and then flushed to disk, so a
sweep killed at any moment leaves whole rows and at most one torn last line, which the next
run cuts off before it appends. The key columns name a run; a run whose key is already in the
file is not run again, unless it crashed or timed out and the sweep retries such runs: its
new row is appended, and where a key has two rows the later one stands.
"""

from __future__ import annotations

import csv
import io
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import ConfigError
from ..params import PARAMS

KEY_COLUMNS = (
    "robot",
    "schedule",
    "structure",
    "size",
    "arms",
    *(p.name for p in PARAMS),
    "spawn_jitter_mm",
    "seed",
)
# BuildResult fields copied into each row, then the run's own wall time and failure reason.
RESULT_FIELDS = (
    "success",
    "bricks_placed",
    "bricks_total",
    "drops",
    "max_slip_mm",
    "worst_error_xy_mm",
    "sim_time_s",
)
RESULT_COLUMNS = (*RESULT_FIELDS, "wall_time_s", "failure_reason")
COLUMNS = KEY_COLUMNS + RESULT_COLUMNS


@dataclass(frozen=True)
class SweepRow:
    """One run of a sweep as `sweep.csv` holds it: every cell as written (`row[column]`), and
    the results typed."""

    cells: Mapping[str, str]

    @classmethod
    def of(cls, row: Mapping[str, Any]) -> SweepRow:
        """A run's values (as `backends.make_row` gives them) spelled as the CSV writes them."""
        return cls({c: _cell(row[c]) for c in COLUMNS})

    def __getitem__(self, column: str) -> str:
        return self.cells[column]

    @property
    def key(self) -> tuple[str, ...]:
        """The key columns' cells: what names the run."""
        return tuple(self.cells[c] for c in KEY_COLUMNS)

    @property
    def success(self) -> bool:
        return self.cells["success"] == "true"

    @property
    def failure_reason(self) -> str:
        """Why the run failed; empty when it succeeded."""
        return self.cells["failure_reason"]

    @property
    def broken(self) -> bool:
        """The run crashed or timed out: its point measures nothing."""
        return self.failure_reason.startswith(("crashed", "timeout"))

    def number(self, column: str) -> float:
        """A numeric cell; NaN when the run measured nothing there (an empty cell)."""
        text = self.cells[column]
        return float(text) if text else math.nan


def row_key(row: SweepRow | Mapping[str, str]) -> tuple[str, ...]:
    return tuple(row[c] for c in KEY_COLUMNS)


class SweepStore:
    """The CSV of one sweep folder: the rows so far, and appending new ones."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self._rows: list[SweepRow] = []
        if path.exists():
            self._repair_and_load()
        # else the file, header first, is written with the first finished run: a sweep that
        # cannot start (a cluster that refuses it) leaves no empty table behind

    def _repair_and_load(self) -> None:
        """Read the rows, having checked the file is a sweep's table before touching it; then
        cut a torn last line (a sweep killed mid-write), or remove a file that holds nothing
        whole, to be written afresh with the first run."""
        raw = self.path.read_bytes()
        whole = raw[: raw.rfind(b"\n") + 1]
        header = _line(COLUMNS).encode()
        if not whole and header.startswith(raw):  # empty, or killed writing the header
            self.path.unlink()
            return
        try:
            reader = csv.DictReader(io.StringIO(whole.decode()))
            fields = tuple(reader.fieldnames or ())
        except (UnicodeDecodeError, csv.Error) as err:
            raise ConfigError(
                f"out: {str(self.path)!r} is not a sweep's table ({err}); accepted a new "
                "folder, or one whose sweep.csv a sweep wrote"
            ) from None
        if fields != COLUMNS:
            raise ConfigError(
                f"out: {str(self.path)!r} has other columns than this version writes; "
                "accepted a new folder or one written by the same version"
            )
        if whole != raw:  # killed mid-write: drop the torn line
            with open(self.path, "r+b") as f:
                f.truncate(len(whole))
        latest: dict[tuple[str, ...], SweepRow] = {}
        for row in reader:  # a retried run's row follows the failed one: the later stands
            latest.pop(row_key(row), None)
            latest[row_key(row)] = SweepRow(row)
        self._rows = list(latest.values())

    def _append_text(self, text: str) -> None:
        fd = os.open(self.path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
        try:
            os.write(fd, text.encode())
            os.fsync(fd)
        finally:
            os.close(fd)

    @property
    def rows(self) -> list[SweepRow]:
        return list(self._rows)

    def done(self, retry_failed: bool = False) -> set[tuple[str, ...]]:
        """The keys of the runs not to run again: every run in the file, or with
        `retry_failed` those that did not crash or time out."""
        return {row_key(r) for r in self._rows if not (retry_failed and r.broken)}

    def append(self, row: dict[str, Any]) -> None:
        """Write one finished run (its values spelled as the row has them)."""
        text_row = SweepRow.of(row)
        if not self.path.exists():
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._append_text(_line(COLUMNS))
        self._append_text(_line([text_row[c] for c in COLUMNS]))
        self._rows = [r for r in self._rows if r.key != text_row.key] + [text_row]


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def _line(cells: Any) -> str:
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerow(list(cells))
    return buffer.getvalue()
