#!/usr/bin/env python3
"""docs/benchmark.md's leaderboard, written from the committed result files: one row a file of
benchmarks/results/ (each written by `benchmarks/baseline.py --row NAME --results
benchmarks/results`), keypose rows first, then continuous, each by success. A number on the
page is a number in a file, never one typed.

    python benchmarks/leaderboard.py [--check]

Writes the table between the page's leaderboard marks; `--check` only says whether the page
holds it (exit 1 if not), as the tests do.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

from pyramid_sim.cli.args import Parser
from pyramid_sim.cli.endings import ended
from pyramid_sim.errors import ConfigError
from pyramid_sim.learning.evaluation.scores import failure_kind
from pyramid_sim.output.files import write_atomic

REPO = Path(__file__).resolve().parents[1]
RESULTS = REPO / "benchmarks" / "results"
PAGE = REPO / "docs" / "benchmark.md"
START, END = "<!-- leaderboard: start -->", "<!-- leaderboard: end -->"
DAGGER_START, DAGGER_END = "<!-- dagger: start -->", "<!-- dagger: end -->"
COLUMNS = (
    "track",
    "task",
    "robot",
    "policy",
    "action mode",
    "inputs",
    "demos",
    "training",
    "success (95 % interval)",
    "films (3D replay)",
    "commit",
    "reproduce",
)
DAGGER_COLUMNS = (
    "row",
    "round",
    "episodes added (beta, kept)",
    "training steps",
    "success",
    "bricks placed",
)
TRACK_ORDER = {"keypose": 0, "continuous": 1}


def load(folder: Path | None = None) -> list[dict[str, Any]]:
    """The result files (of benchmarks/results/ by default), in the table's order; ConfigError
    naming the first that is not a row's result file (each is read and its cells made here,
    before the page is touched)."""
    rows = [_read(path) for path in sorted((folder or RESULTS).glob("*.json"))]
    return sorted(rows, key=_order)


def _order(row: dict[str, Any]) -> tuple[int, float, str]:
    return TRACK_ORDER[row["track"]], -float(row["score"]["success_rate"]), str(row["row"])


def _read(path: Path) -> dict[str, Any]:
    """`path`'s row, every cell of it made once to prove it can be; ConfigError otherwise."""
    accepted = "accepted a result file benchmarks/baseline.py --results wrote"
    try:
        row = json.loads(path.read_bytes())
        if not isinstance(row, dict):
            raise TypeError(f"a JSON {type(row).__name__}, not an object")
        if row.get("track") not in TRACK_ORDER:
            raise ValueError(f"its track {row.get('track')!r} is not one of {tuple(TRACK_ORDER)}")
        if not isinstance(row["score"]["success_rate"], (int, float)):
            raise TypeError(f"its success rate {row['score']['success_rate']!r} is no number")
        _order(row)
        table([row])
        dagger_table([row])
    except IsADirectoryError:
        raise ConfigError(f"results: {str(path)!r} is a folder; {accepted}") from None
    except (OSError, ValueError, TypeError, KeyError, IndexError, AttributeError) as err:
        what = f"lacks {err}" if isinstance(err, KeyError) else str(err)
        raise ConfigError(
            f"results: {str(path)!r} is not a row's result ({what}); {accepted}"
        ) from None
    if row["row"] != path.stem:  # a copy under another name would be a second row
        raise ConfigError(
            f"results: {str(path)!r} holds the row {row['row']!r}, not {path.stem!r}; "
            f"accepted {row['row']}.json, as baseline.py names it"
        )
    return row


def _task(row: dict[str, Any]) -> str:
    task = row["task"]
    variation = "" if task["variation"] == "layout" else f", {task['variation']}"
    trained = task.get("trained_layers", task["layers"])
    learned = "" if trained == task["layers"] else f"; trained on {trained} layers"
    return f"{task['structure']} {task['layers']} ({task['bricks']} bricks{variation}{learned})"


def _demos(row: dict[str, Any]) -> str:
    demos = row["demos"]
    text = f"{demos['built']} of {demos['recorded']} built"
    rounds = (row.get("dagger") or {}).get("rounds") or []
    if rounds:
        many = f"{len(rounds)} round" + ("s" if len(rounds) > 1 else "")
        text += f" + {sum(r['episodes'] for r in rounds)} DAgger ({many})"
    return text


def _training(row: dict[str, Any]) -> str:
    seconds, found = row["seconds"], row["machine"]
    cpu = seconds.get("train_cpu")
    cost = f"{cpu / 60:.0f} min of one core" if cpu is not None else "?"
    where = found["gpu"] or f"{found['cores']}-core CPU, no GPU"
    return f"{row['training_steps']} steps, {cost} ({where})"


def _success(row: dict[str, Any]) -> str:
    score = row["score"]
    low, high = (100 * v for v in score["success_rate_95"])
    return (
        f"**{score['successes']}/{score['episodes']}** ({low:.0f}-{high:.0f} %), "
        f"{score['bricks_placed_mean']:.2f} bricks placed"
    )


def films(row: dict[str, Any], folder: Path | None = None) -> dict[str, dict[str, Any]]:
    """The row's filmed episodes (kind -> the manifest's entry: the episode, its film's and
    replay page's names) that benchmarks/films.py chose from the row's own run (its manifest's
    row and finish time are the row's), from results/films/ (or `folder`). The manifest is
    committed; the films and pages it names are made beside it and never committed."""
    folder = folder or RESULTS / "films"
    manifest = folder / f"{row['row']}.json"
    if not manifest.is_file():
        return {}
    document = json.loads(manifest.read_text())
    if document.get("row") != row["row"] or document.get("finished") != row.get("finished"):
        return {}
    return dict(document.get("films", {}))


def _films(row: dict[str, Any], folder: Path | None) -> str:
    """The filmed episodes by seed (the same on every machine, films made or not)."""
    cells = []
    for kind, made in films(row, folder).items():
        episode = made["episode"]
        why = f", {failure_kind(episode['failure']) or 'other'}" if episode["failure"] else ""
        cells.append(f"{kind}: seed {episode['seed']}{why}")
    return ", ".join(cells) or "-"


def header(columns: tuple[str, ...]) -> list[str]:
    """A markdown table's first two lines: its columns' names and the line under them."""
    return ["| " + " | ".join(columns) + " |", "|" + " --- |" * len(columns)]


def table(rows: list[dict[str, Any]], films_folder: Path | None = None) -> str:
    """The leaderboard's markdown table (the films from results/films/, or `films_folder`)."""
    lines = header(COLUMNS)
    for row in rows:
        cells = (
            row["track"],
            _task(row),
            row["robot"],
            row["policy"],
            row["action_mode"],
            ", ".join(row["inputs"]),
            _demos(row),
            _training(row),
            _success(row),
            _films(row, films_folder),
            row["commit"][:7] + ("+" if "+" in row["commit"] else ""),
            f"`{row['command']}`",
        )
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def dagger_table(rows: list[dict[str, Any]]) -> str:
    """Each row's DAgger rounds, one line a round: what it added and what its policy scored
    (round 0 is the first training's), from the rows whose result files hold the scores."""
    lines = header(DAGGER_COLUMNS)
    for row in rows:
        dagger = row.get("dagger") or {}
        added = {k + 1: r for k, r in enumerate(dagger.get("rounds") or [])}
        for scored in dagger.get("scores") or []:
            k, low, high = scored["round"], *(100 * v for v in scored["success_rate_95"])
            done = added.get(k)
            what = (
                f"{done['episodes']} (beta {done['beta']:g}, {done['kept']} kept)" if done else "-"
            )
            steps = done["steps"] if done else row["recipe"]["steps"]
            lines.append(
                f"| {row['row']} | {k} | {what} | {steps} | {scored['successes']}/"
                f"{scored['episodes']} ({low:.0f}-{high:.0f} %) | "
                f"{scored['bricks_placed_mean']:.2f} |"
            )
    return "\n".join(lines)


def _between(text: str, start: str, end: str, table_text: str) -> str:
    if start not in text or end not in text:
        raise SystemExit(f"{PAGE}: the marks {start} and {end} are missing")
    head, rest = text.split(start, 1)
    _, tail = rest.split(end, 1)
    return f"{head}{start}\n{table_text}\n{end}{tail}"


def page_with(text: str, rows: list[dict[str, Any]]) -> str:
    """The page `text` with its leaderboard and DAgger's rounds (each between its marks)
    written from `rows`."""
    text = _between(text, START, END, table(rows))
    return _between(text, DAGGER_START, DAGGER_END, dagger_table(rows))


def main(argv: list[str] | None = None) -> int:
    return ended("benchmarks/leaderboard.py", lambda: _run(argv))


def _run(argv: list[str] | None) -> int:
    parser = Parser(prog="benchmarks/leaderboard.py", description=__doc__.splitlines()[0])
    parser.add_argument(
        "--check",
        action="store_true",
        help="only say whether the page holds the table (exit 1 if not)",
    )
    args, unknown = parser.parse_known_args(argv)
    if unknown:
        parser.error(
            f"{' '.join(unknown)!r} is not a flag of this script; accepted --check, or none"
        )
    text = PAGE.read_text()
    wanted = page_with(text, load())
    if args.check:
        if wanted != text:
            print(f"{PAGE} does not hold the results' leaderboard: run {__file__}")
            return 1
        return 0
    write_atomic(PAGE, lambda tmp: tmp.write_text(wanted))
    return 0


if __name__ == "__main__":
    sys.exit(main())
