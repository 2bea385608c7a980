"""baseline.py's command line: a leaderboard row's recipe by name (benchmarks/rows.py), each
other flag changing one of its values, all checked before anything is made, the run's
folder included (one of its own runs to go on with, or new)."""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))  # rows.py beside it

from row_paths import RUN_NAMES  # noqa: E402
from rows import ROWS, Recipe, quick  # noqa: E402
from script_checks import check_run_folder  # noqa: E402

from pyramid_sim.choices import FPS_CHOICES, RECORD_ACTION_MODES  # noqa: E402
from pyramid_sim.cli.args import (  # noqa: E402
    Parser,
    bounded,
    image_size,
    number,
    one_of,
    output_path,
    whole,
)
from pyramid_sim.errors import ConfigError  # noqa: E402
from pyramid_sim.params import LINGER  # noqa: E402
from pyramid_sim.robots import PRESETS  # noqa: E402

# the recipe's values a flag of the same name gives as parsed
AS_PARSED = (
    "robot",
    "structure",
    "layers",
    "variation",
    "steps",
    "demos",
    "noise",
    "linger",
    "episodes",
    "action_mode",
    "image_size",
)
COUNTS = ("steps", "demos", "episodes", "workers")  # each 1 or more


def parse(argv: list[str] | None, description: str) -> tuple[Path, Recipe, Path | None]:
    """The run's folder, its recipe and the folder to publish its result file in (or None);
    a bad flag exits 2 with one line, before anything is made."""
    parser = Parser(prog="benchmarks/baseline.py", description=description)
    _run_flags(parser)
    _recipe_flags(parser)
    args = parser.parse_args(argv)
    if args.quick and args.results is not None:  # its 4-step policy is no row
        parser.error(
            "results: a --quick run publishes no row; accepted --results without --quick, "
            "or --quick alone"
        )
    if args.curve < 0:
        parser.error(f"curve: {args.curve} is out of range; accepted 0 (no curve) or more seeds")
    recipe = replace(ROWS[args.row], curve_episodes=args.curve, workers=args.workers)
    if args.quick:  # its rounds' scores too, on the quick evaluation's seeds
        recipe = quick(recipe)
        recipe = replace(recipe, round_episodes=min(recipe.round_episodes, recipe.episodes))
    recipe = replace(recipe, **given(args))
    if args.rounds is not None:
        if not 0 <= args.rounds <= len(recipe.rounds):
            parser.error(
                f"rounds: {args.rounds} is out of range; accepted 0 to {len(recipe.rounds)}, "
                f"the rounds of row {recipe.row}"
            )
        recipe = replace(recipe, rounds=recipe.rounds[: args.rounds])
    for name in COUNTS:
        if getattr(recipe, name) < 1:
            parser.error(f"{name}: {getattr(recipe, name)}; accepted 1 or more")
    try:
        check_run_folder(args.out, RUN_NAMES, "baseline.py")
    except ConfigError as err:
        parser.error(str(err))
    return args.out, recipe, args.results


def given(args: argparse.Namespace) -> dict[str, Any]:
    """The recipe's values the flags give; those not given stay the row's."""
    values = {name: getattr(args, name) for name in AS_PARSED}
    if args.fps is not None:
        values["fps"] = int(args.fps)
    if args.cameras is not None:
        values["cameras"] = tuple(c for c in args.cameras.split(",") if c)
    return {k: v for k, v in values.items() if v is not None}


def _run_flags(parser: Parser) -> None:
    """The run's own flags: where it goes, which row, how much of it."""
    add = parser.add_argument
    add("--out", type=output_path("out", folder=True), required=True)
    add(
        "--row",
        type=one_of("row", tuple(ROWS)),
        default="panda-2",
        help="a leaderboard row's recipe (default panda-2)",
    )
    add(
        "--results",
        type=output_path("results", folder=True),
        default=None,
        help="also write the row's result file here, as NAME.json",
    )
    add("--quick", action="store_true", help="a few of each (CI's round trip)")


def _recipe_flags(parser: Parser) -> None:
    """The flags that change one of the row's values (the workers and the curve's seeds too:
    a row leaves them at 1 and 0)."""
    add = parser.add_argument
    add("--robot", type=one_of("robot", tuple(PRESETS)), default=None)
    add("--structure", default=None)
    add("--layers", type=whole("layers"), default=None)
    variations = ("fixed", "layout", "full")
    add("--variation", type=one_of("variation", variations), default=None)
    add("--cameras", default=None, help="cameras the policy sees (default none)")
    size_help = "N or HxW: the cameras' images (default record's)"
    add("--image-size", type=image_size, default=None, help=size_help)
    add("--steps", type=whole("steps"), default=None, help="training steps")
    add("--demos", type=whole("demos"), default=None)
    noise_help = "DART: rad of joint actions, m of waypoints"
    add("--noise", type=number("noise"), default=None, help=noise_help)
    add(
        "--linger", type=bounded(LINGER), default=None, help="s recorded after each build's success"
    )
    mode_help = "the action's form (default the recipe's)"
    add("--action-mode", choices=RECORD_ACTION_MODES, default=None, help=mode_help)
    fps = one_of("fps", tuple(map(str, FPS_CHOICES)))
    add("--fps", type=fps, default=None, help="steps a second (default the recipe's)")
    rounds = whole("rounds", "0 to the row's rounds")
    add(
        "--rounds",
        type=rounds,
        default=None,
        help="DAgger's rounds run, of the row's (default all)",
    )
    add("--episodes", type=whole("episodes"), default=None, help="evaluated")
    add("--workers", type=whole("workers"), default=1, help="recording and evaluating them")
    add("--curve", type=whole("curve"), default=0, help="score every checkpoint on N seeds")
