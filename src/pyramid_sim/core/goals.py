"""Place goals from a file (the Brick Manager's fixed list): JSON or CSV of x, y, z, yaw per
brick, in build order. Pure: every problem is a ConfigError naming the file and the row, among
them goals that overlap, float or would tip (core/support.py).

JSON: `{"goals": [{"x": .., "y": .., "z": .., "yaw": ..}, ...]}` or the list alone.
CSV: a header line `x,y,z,yaw`, then one brick a line. Metres and radians, world frame, z the
brick's resting centre height; `yaw` may be left out (0: long axis pointing away).
"""

from __future__ import annotations

import csv
import io
import json
import math
import stat
from pathlib import Path

from ..config import BrickConfig
from ..errors import ConfigError
from ..params import parse_number, span_text
from .poses import Pose
from .structures import BrickTarget
from .support import TOLERANCE, first_fault

COLUMNS = ("x", "y", "z", "yaw")
REQUIRED = ("x", "y", "z")
MAX_GOALS = 200
MAX_BYTES = 1_000_000  # far more than MAX_GOALS rows need; a larger file is not a goals list
# Sane bounds, far beyond any arm's reach (the reach check then names the arms' own limit):
# a value past them is a typo, and would overflow the arithmetic that follows.
MAX_COORDINATE = 10.0  # m, either way
MAX_YAW = 2 * math.pi  # rad, a turn either way


def load_goals(path: Path, brick: BrickConfig, table_z: float) -> tuple[BrickTarget, ...]:
    """The goals of `path` as targets, each in a course counted from `table_z` (the resting
    centre height of a brick on the table). Refuses unknown columns, non-numbers, goals below
    the table or between courses, and bricks that overlap, float or would tip, naming the row
    (1 = first goal): a build of them would fail without saying why."""
    name = path.name
    text = _read_text(path)
    rows = _json_rows(text, name) if path.suffix.lower() == ".json" else _csv_rows(text, name)
    if not rows:
        raise ConfigError(f"goals: {name} holds no goals; accepted 1 to {MAX_GOALS}")
    if len(rows) > MAX_GOALS:
        raise ConfigError(f"goals: {name} holds {len(rows)} goals; accepted 1 to {MAX_GOALS}")
    text_numbers = path.suffix.lower() != ".json"  # CSV holds text; JSON has numbers of its own
    targets = [
        _target(i, row, name, brick, table_z, text_numbers) for i, row in enumerate(rows, start=1)
    ]
    # Every plan lays the courses bottom first, keeping the file's order within a course.
    order = sorted(range(len(targets)), key=lambda i: targets[i].layer)
    fault = first_fault([targets[i].pose for i in order], brick, table_z)
    if fault is not None:
        raise ConfigError(f"goals: {name} {fault.describe(lambda k: f'row {order[k] + 1}')}")
    return tuple(targets)


def _read_text(path: Path) -> str:
    """The file's text, as UTF-8 (a byte-order mark allowed, as spreadsheets write one);
    ConfigError for a file that cannot be read, is too large, or is not UTF-8 text."""
    where = f"goals: {path.name}"
    try:
        mode = path.stat().st_mode
    except OSError as err:
        raise ConfigError(f"goals: cannot read {str(path)!r} ({err.strerror})") from None
    if not stat.S_ISREG(mode):  # a FIFO or a device would be read forever, a folder not at all
        raise ConfigError(
            f"goals: {str(path)!r} is not a regular file ({_kind(mode)}); accepted a JSON or "
            "CSV file"
        )
    try:
        with path.open("rb") as file:
            data = file.read(MAX_BYTES + 1)
    except OSError as err:
        raise ConfigError(f"goals: cannot read {str(path)!r} ({err.strerror})") from None
    if len(data) > MAX_BYTES:
        raise ConfigError(f"{where} is over {MAX_BYTES:,} bytes; accepted 1 to {MAX_GOALS} goals")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise ConfigError(
            f"{where} is not UTF-8 text (byte {err.start} is 0x{data[err.start]:02x}); "
            "accepted JSON or CSV in UTF-8"
        ) from None


def _kind(mode: int) -> str:
    """What a file of `mode` is, in words, where it is not a regular file."""
    kinds = (
        (stat.S_ISDIR, "a folder"),
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISSOCK, "a socket"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
    )
    return next((name for test, name in kinds if test(mode)), "not a file")


def _json_rows(text: str, name: str) -> list[dict]:
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as err:
        raise ConfigError(f"goals: {name} is not JSON ({err.msg}, line {err.lineno})") from None
    except RecursionError:
        raise ConfigError(f"goals: {name} is not a goals list (nested too deep)") from None
    except ValueError:  # an int of more digits than Python converts (4300)
        raise ConfigError(f"goals: {name} is not a goals list (a number too long)") from None
    rows = doc.get("goals") if isinstance(doc, dict) else doc
    if not isinstance(rows, list) or not all(isinstance(r, dict) for r in rows):
        raise ConfigError(
            f'goals: {name} must hold a list of {{x, y, z, yaw}} objects, alone or under "goals"'
        )
    return rows


def _csv_rows(text: str, name: str) -> list[dict]:
    reader = csv.DictReader(io.StringIO(text))
    if reader.fieldnames is None:
        raise ConfigError(
            f"goals: {name} is empty; accepted a header x,y,z,yaw and one row a brick"
        )
    rows = []
    try:
        for row in reader:
            if None in row:
                raise ConfigError(
                    f"goals: {name} row {reader.line_num - 1}: more values than columns"
                )
            rows.append({k.strip(): v for k, v in row.items()})
    except csv.Error as err:  # a field over csv's size limit, a NUL byte
        raise ConfigError(f"goals: {name} line {reader.line_num}: not CSV ({err})") from None
    return rows


def _target(
    i: int, row: dict, name: str, brick: BrickConfig, table_z: float, text_numbers: bool
) -> BrickTarget:
    where = f"goals: {name} row {i}"
    unknown = [k for k in row if k not in COLUMNS]
    if unknown:
        raise ConfigError(f"{where}: unknown column {unknown[0]!r}; accepted {', '.join(COLUMNS)}")
    missing = [k for k in REQUIRED if k not in row or row[k] in ("", None)]
    if missing:
        raise ConfigError(f"{where}: no {missing[0]}; accepted columns {', '.join(COLUMNS)}")
    values = {key: _value(row, key, where, text_numbers) for key in COLUMNS}
    layer = round((values["z"] - table_z) / brick.height)
    if layer < 0 or abs(values["z"] - table_z - layer * brick.height) > TOLERANCE:
        raise ConfigError(
            f"{where}: z {values['z']:g} is not a resting height; accepted {table_z:g} + k x "
            f"{brick.height:g} (k = 0, 1, ...) within {TOLERANCE * 1000:g} mm"
        )
    pose = Pose(values["x"], values["y"], table_z + layer * brick.height, values["yaw"])
    return BrickTarget(pose, layer)


def _value(row: dict, key: str, where: str, text_numbers: bool) -> float:
    """The row's `key` as a float within its sane bound (0 if left out); ConfigError naming
    the row, the column and the accepted range otherwise. A number written as text is one
    only where the file is text (CSV): in JSON, "0.7" is a string, as `true` is not 1."""
    raw = row.get(key, 0.0)
    if isinstance(raw, str) and not text_numbers:
        raise ConfigError(f"{where}: {key} {_quoted(raw)} is a string; accepted a JSON number")
    raw = 0.0 if raw in ("", None) else raw
    try:
        if isinstance(raw, bool):
            raise ValueError
        value = parse_number(raw.strip()) if isinstance(raw, str) else float(raw)
    except (TypeError, ValueError):
        raise ConfigError(f"{where}: {key} {_quoted(raw)} is not a number") from None
    except OverflowError:  # an int past any float
        value = math.inf
    limit, unit = (MAX_YAW, "rad") if key == "yaw" else (MAX_COORDINATE, "m")
    if not math.isfinite(value) or abs(value) > limit:
        raise ConfigError(
            f"{where}: {key} {value:g} is out of range; accepted {span_text(-limit, limit)} {unit}"
        )
    return value


def _quoted(raw: object) -> str:
    """A value that is not a number as the message shows it: quoted, and cut short."""
    text = repr(raw)
    return text if len(text) <= 40 else f"{text[:37]}..."
