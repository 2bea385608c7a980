#!/usr/bin/env python3
"""The learned baseline, end to end: the expert's demonstrations recorded with DART's noise,
a policy trained on them by lerobot's own `lerobot-train`, DAgger's rounds (the policy
drives, the expert labels what it reaches, and the policy is trained on with them), and the
last policy scored by `pyramid-sim evaluate` on held-out seeds.

    python benchmarks/baseline.py --out DIR [--row NAME] [--results DIR] [--quick]
                                  [--robot R] [--structure S --layers N] [--variation V]
                                  [--cameras A,B --image-size N] [--steps N] [--curve N]
                                  [--action-mode M] [--noise X] [--linger S] [--rounds N]

`--row NAME` is a leaderboard row's whole recipe (benchmarks/rows.py; an unknown name lists
them); the other flags change it. Run it with the python of a venv that holds lerobot 0.6.1,
pyramid_sim and its lerobot plugin (docs/benchmark.md says how). It writes DIR/demos (the
dataset, DAgger's episodes added to it), DIR/train (lerobot's first run) and DIR/train_rK
(round K's; the plugin's env in each checkpoint's train_config.json, so `pyramid-sim evaluate
--policy CKPT` needs no flags), DIR/lerobot_eval.txt (the lerobot-eval line that scores the
last checkpoint on the same seeds: lerobot-eval reads no env from a checkpoint, so it repeats
the env's flags), DIR/evaluation.json (the score, with its inputs and versions), DIR/result.json
(the row's result file: its recipe, versions, commit, machine, seconds and score; with
`--results DIR2` also DIR2/NAME.json, as benchmarks/results/ keeps them) and, with `--curve
N`, DIR/curve.json and DIR/curve.png: every saved checkpoint of the last training scored on N
seeds. A run stopped midway goes on from where it stopped (the demos, every round's episodes
and every finished training kept). Seeds are fixed: demos from 0 (DAgger's episodes after
them), evaluation from 100000, training seed 0. `--quick` does a few of each. On a terminal
each stage shows a bar of what it has done and the time left (the training's read off its
log); in a log, none.

Each job has its module beside this one: row_flags.py (the command line), row_recording.py,
row_training.py, row_dagger.py, row_scoring.py, row_curve.py, row_result.py (the result
file), row_paths.py (where the files lie) and stage_progress.py (the bars).
"""

from __future__ import annotations

import json
import sys
import time
from dataclasses import asdict
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))  # rows.py beside it

from films import films_beside  # noqa: E402
from row_curve import curve  # noqa: E402
from row_dagger import dagger  # noqa: E402
from row_flags import parse as parse_flags  # noqa: E402
from row_paths import checkpoint, evaluated, write_whole  # noqa: E402
from row_recording import record  # noqa: E402
from row_result import result  # noqa: E402
from row_scoring import lerobot_eval_line, round_scores, score  # noqa: E402
from row_training import train, trained_before  # noqa: E402
from rows import ROWS, Recipe, Round  # noqa: E402
from script_checks import check_recipe, lerobot_needed  # noqa: E402

from pyramid_sim.cli.args import EXIT_USAGE  # noqa: E402
from pyramid_sim.cli.endings import ended  # noqa: E402
from pyramid_sim.errors import PyramidSimError  # noqa: E402

__all__ = ["ROWS", "Recipe", "Round", "main", "parse"]


def parse(argv: list[str] | None) -> tuple[Path, Recipe, Path | None]:
    """The run's folder, its recipe and where to publish its result file (row_flags.py)."""
    return parse_flags(argv, description=__doc__.splitlines()[0])


def main(argv: list[str] | None = None) -> int:
    """The row run end to end, or one line and its exit status (benchmarks/script_checks.py
    checks all first: nothing is made for a bad flag)."""
    return ended("benchmarks/baseline.py", lambda: _run(*parse(argv)))


def _run(out: Path, recipe: Recipe, results: Path | None) -> int:
    lerobot_needed("the baseline's training")  # before any recording
    check_recipe(recipe)  # all the library would refuse midway, before anything is made
    try:
        out.mkdir(parents=True, exist_ok=True)
        seconds, rounds, gain = _train(out, recipe)
        last = checkpoint(out, len(recipe.rounds))
        write_whole(out / "lerobot_eval.txt", lerobot_eval_line(last, out, recipe) + "\n")
        start = time.perf_counter()
        scored = evaluated(out, recipe)
        scores = score(last, recipe, recipe.episodes, scored, recipe.eval_layers)
        seconds["evaluate"] = time.perf_counter() - start
        if recipe.curve_episodes:
            curve(out, recipe)
    except PyramidSimError as error:
        print(f"baseline: {error}", file=sys.stderr)
        (out / "failed.txt").write_text(f"{error}\n")
        return EXIT_USAGE if "accepted" in str(error) else 1
    row = _publish(out, recipe, results, scored, seconds, rounds, gain)
    films_beside(last, recipe, scored, (results or out) / "films", row)  # films.py
    print(
        f"baseline {recipe.row}: {scores['successes']}/{scores['episodes']} built "
        f"({100 * scores['success_rate']:.0f} %), trained {recipe.steps} steps in "
        f"{seconds['train'] / 60:.1f} min -> {out / 'result.json'}"
    )
    return 0


def _train(
    out: Path, recipe: Recipe
) -> tuple[dict[str, float], list[dict[str, Any]], list[dict[str, Any]]]:
    """The demonstrations, the first training and DAgger's rounds, each found done or done
    now, and each round's policy scored: the seconds each took, the rounds and their gain."""
    seconds = {"record": record(out, recipe)}
    before = trained_before(out, steps=recipe.steps)
    seconds["train"] = before if before is not None else train(out, recipe)
    rounds = dagger(out, recipe, seconds)
    start = time.perf_counter()
    gain = round_scores(out, recipe) if recipe.round_episodes else []
    seconds["round_scores"] = time.perf_counter() - start
    cpu = sorted(out.glob("train*_cpu_s.txt"))
    if cpu:
        seconds["train_cpu"] = sum(float(p.read_text()) for p in cpu)
    return seconds, rounds, gain


def _publish(
    out: Path,
    recipe: Recipe,
    results: Path | None,
    scored: Path,
    seconds: dict[str, float],
    rounds: list[dict[str, Any]],
    gain: list[dict[str, Any]],
) -> str:
    """The row's files: its evaluation.json with the recipe and seconds added, DIR/result.json
    and, with `results`, results/NAME.json; the result file's text."""
    document = json.loads((scored / "evaluation.json").read_text())
    document["baseline"] = {"recipe": asdict(recipe), "seconds": seconds}
    write_whole(scored / "evaluation.json", json.dumps(document, indent=1) + "\n")
    row = json.dumps(result(recipe, document, seconds, out / "demos", rounds, gain), indent=1)
    row += "\n"
    write_whole(out / "result.json", row)
    if results is not None:
        results.mkdir(parents=True, exist_ok=True)
        write_whole(results / f"{recipe.row}.json", row)
    return row


if __name__ == "__main__":
    sys.exit(main())
