"""The command line's flags for a task spec's fields (learning/task/spec.py), made from the
fields: each flag's name, help and accepted values are its field's declaration, and its parser
follows the field's type. docs/cli.md's table of them is `table()`, read off the parser
(tests/test_task_flags.py holds the two equal; `python3 scripts/task_flags_table.py`
writes it there)."""

from __future__ import annotations

import argparse
from collections.abc import Callable, Mapping, Sequence
from dataclasses import MISSING, Field, fields
from typing import Any

from ..learning.task.spec import TaskSpec
from ..params import LINGER
from .args import bounded, image_size, whole

# The fields offered as flags, in the help's order
EPISODE_FIELDS = ("variation", "fps", "action_mode")  # record's and evaluate's
RECORD_FIELDS = ("cameras", "image_size", "randomize", "linger")  # and the switches
BOUNDS = {"linger": LINGER}  # a float field's range, checked as its flag is read


def flagged() -> dict[str, Field[Any]]:
    """The spec's fields that have a flag, by name."""
    return {f.name: f for f in fields(TaskSpec) if f.metadata["flag"]}


def add_task_flags(
    p: argparse.ArgumentParser,
    names: Sequence[str],
    defaults: Mapping[str, Any],
    choices: Mapping[str, Sequence[str] | Mapping[str, str]] | None = None,
) -> None:
    """Each field of `names` as its flag, its value under the field's name (a bool's flag
    turns it off). `defaults`: the command's, shown as text where the flag reads text;
    `choices`: a field's choices where the command names them (fewer than the spec, or each
    in a few words)."""
    declared = flagged()
    for name in names:
        f = declared[name]
        meta, default = f.metadata, defaults.get(name, _default(f))
        if f.type == "bool":
            help_ = f"{meta['doc']} (default on)"
            p.add_argument(meta["flag"], dest=name, action="store_false", help=help_)
            continue
        offered = (choices or {}).get(name)
        shown = offered.values() if isinstance(offered, Mapping) else offered
        accepted = ", ".join(shown) if shown else meta["accepted"]
        p.add_argument(
            meta["flag"],
            dest=name,
            default=default,
            type=_parser(f),  # text stays text
            choices=list(offered) if offered else None,
            metavar=_metavar(f),
            help=f"{meta['doc']}; accepted {accepted} (default {_shown(name, default)})",
        )


def switches() -> tuple[str, ...]:
    """The flagged fields that are bools: each flag turns its field off."""
    return tuple(name for name, f in flagged().items() if f.type == "bool")


def task_values(args: argparse.Namespace) -> dict[str, Any]:
    """The spec's fields as their flags gave them (those the command offers)."""
    return {name: getattr(args, name) for name in flagged() if name in vars(args)}


def _default(f: Field[Any]) -> Any:
    return f.default if f.default is not MISSING else None


def _parser(f: Field[Any]) -> Callable[[str], Any]:
    """How a flag's text becomes the field's value: a whole number, a bounded one, an image's
    size; names and words stay text (a list's parse is the command's: `none` means none)."""
    if f.type == "int":
        return whole(f.name, f.metadata["accepted"])
    if f.type == "float":
        return bounded(BOUNDS[f.name])
    if f.type == "tuple[int, int]":
        return image_size
    return str


def _metavar(f: Field[Any]) -> str | None:
    return {"tuple[str, ...]": "A,B,...", "tuple[int, int]": "H[xW]", "float": "SECONDS"}.get(
        f.type if isinstance(f.type, str) else ""
    )


def _shown(name: str, default: Any) -> str:
    if default is None and name == "image_size":
        return "224"
    if isinstance(default, (tuple, list)):
        return ",".join(map(str, default)) or "none"
    if default == "":
        return "none"
    return f"{default:g}" if isinstance(default, float) else str(default)


def table(record: argparse.ArgumentParser) -> str:
    """docs/cli.md's table of the spec's flags, read off `record`'s parser: each flag, the
    field it sets and its help, as `pyramid-sim record --help` prints it."""
    declared = flagged()
    rows = ["| flag | field | help |", "|---|---|---|"]
    for action in record._actions:
        if action.dest in declared:
            rows.append(f"| `{action.option_strings[0]}` | `{action.dest}` | {action.help} |")
    return "\n".join(rows) + "\n"


START, END = "<!-- task-spec flags: start -->", "<!-- task-spec flags: end -->"


def in_docs(text: str) -> str:
    """The table between docs/cli.md's markers."""
    return text.split(START, 1)[1].split(END, 1)[0].strip("\n") + "\n"


def written(text: str, record: argparse.ArgumentParser) -> str:
    """docs/cli.md's `text` with the table of `record`'s parser made afresh between its
    markers."""
    head, rest = text.split(START, 1)
    return f"{head}{START}\n{table(record)}{END}{rest.split(END, 1)[1]}"
