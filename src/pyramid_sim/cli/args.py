"""The command line's arguments: generated from the parameter table (physics flags, sweep axes)
and the structure catalogue (size options and their defaults), then turned into settings.

Ranges are checked by the settings classes, not here, so a value is accepted or refused for
the same reason whichever way it arrives.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import NoReturn

from ..choices import ARM_CHOICES, BACKENDS, SCHEDULES
from ..config import SPAWN_JITTER_MM, SimConfig
from ..core.structures import (
    MAX_BRICKS,
    MAX_COURSE,
    MAX_LAYERS,
    STRUCTURES,
    StructureSpec,
)
from ..params import IMAGE_SIZE_TEXT, PARAMS, Bound, image_size_fits, parse_number, parse_whole
from ..robots import DEFAULT_ROBOT, PRESETS
from .paths import path_problem

EXIT_FAILED = 1
EXIT_USAGE = 2

# size option -> (flag, accepted values). `width` is `--wall-width`, never taken for the video's
# (`--video-width`).
SIZE_FLAGS = {
    "layers": ("--layers", f"1 to {MAX_LAYERS}"),
    "bricks": ("--bricks", f"1 to {MAX_BRICKS}"),
    "width": ("--wall-width", f"1 to {MAX_COURSE}"),
    "towers": ("--towers", f"1 to {MAX_COURSE}"),
}


class Parser(argparse.ArgumentParser):
    """An argument parser whose refusals are one line and exit status 2, with no usage block."""

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")


def number(name: str) -> Callable[[str], float]:
    """Text to float; the range (and NaN, inf) is checked by the settings classes."""

    def parse(text: str) -> float:
        try:
            return parse_number(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name}: {text!r} is not a number") from None

    return parse


def bounded(bound: Bound) -> Callable[[str], float]:
    """A flag's number, refused here when outside `bound` (before anything is imported)."""

    def parse(text: str) -> float:
        value = number(bound.name)(text)
        if not bound.low <= value <= bound.high:
            raise argparse.ArgumentTypeError(
                f"{bound.name}: {text!r} is out of range; accepted {bound.text}"
            )
        return value

    return parse


def whole(name: str, accepted: str = "") -> Callable[[str], int]:
    """Text to int; the range is checked where the value is used (settings, StructureSpec)."""

    def parse(text: str) -> int:
        try:
            return parse_whole(text)
        except ValueError:
            hint = f"; accepted {accepted}" if accepted else ""
            raise argparse.ArgumentTypeError(
                f"{name}: {text!r} is not a whole number{hint}"
            ) from None

    return parse


def image_size(text: str) -> tuple[int, int]:
    """`H` (square) or `HxW`, in pixels."""
    try:
        parts = [parse_whole(v) for v in text.lower().split("x")]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"image size: {text!r} is not a size; accepted N or HxW, {IMAGE_SIZE_TEXT}"
        ) from None
    if len(parts) == 1:
        parts = parts * 2
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"image size: {text!r}; accepted N or HxW")
    height, width = parts
    if not image_size_fits(height, width):
        raise argparse.ArgumentTypeError(f"image size: {text!r}; accepted {IMAGE_SIZE_TEXT}")
    return height, width


def one_of(name: str, options: Sequence[str]) -> Callable[[str], str]:
    def parse(text: str) -> str:
        if text not in options:
            raise argparse.ArgumentTypeError(
                f"{name}: unknown {text!r}; accepted {', '.join(options)}"
            )
        return text

    return parse


def output_path(what: str, *, folder: bool) -> Callable[[str], Path]:
    """Text to the path of an output (a folder, or a file when not `folder`), refusing at once
    what would otherwise fail midway or write somewhere unmeant: an empty path (it would be
    the working folder), a name longer than its file system takes, and a file's path that
    names a folder. Every --out, --video and --snapshot is read through this."""
    kind = "folder" if folder else "file"

    def parse(text: str) -> Path:
        problem = path_problem(text, folder)
        if problem:
            raise argparse.ArgumentTypeError(f"{what}: {problem}; accepted a {kind}'s path")
        return Path(text)

    return parse


def _size_help(option: str) -> str:
    users = [f"{n} ({d.sizes[option]})" for n, d in STRUCTURES.items() if option in d.sizes]
    return f"{', '.join(users)}; accepted {SIZE_FLAGS[option][1]} (defaults in brackets)"


def add_robot_arg(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--robot",
        type=one_of("robot", tuple(PRESETS)),
        default=DEFAULT_ROBOT,
        metavar="|".join(PRESETS),
        help=f"{', '.join(f'{n} ({r.summary})' for n, r in PRESETS.items())}; "
        f"default {DEFAULT_ROBOT}",
    )


def add_schedule_arg(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--schedule",
        type=one_of("schedule", SCHEDULES),
        default=SCHEDULES[0],
        metavar="|".join(SCHEDULES),
        help="lockstep: the seed's four phases (default); overlap: each arm carries "
        "its brick straight to its place, the arms taking turns in the zone",
    )


def add_structure_args(p: argparse.ArgumentParser) -> None:
    add_robot_arg(p)
    names = sorted(STRUCTURES)
    p.add_argument(
        "--structure",
        type=one_of("structure", names),
        default="pyramid-even",
        metavar="NAME",
        help=f"{', '.join(names)} (default pyramid-even)",
    )
    for option, (flag, accepted) in SIZE_FLAGS.items():
        p.add_argument(
            flag,
            metavar="N",
            type=whole(flag[2:].replace("-", " "), accepted),
            help=_size_help(option),
        )
    p.add_argument(
        "--goals",
        type=Path,
        metavar="FILE",
        help="list: place goals, JSON or CSV of x, y, z, yaw (examples in "
        "pyramid_sim/assets/goals/)",
    )
    p.add_argument(
        "--arms",
        type=one_of("arms", ARM_CHOICES),
        default="both",
        metavar="|".join(ARM_CHOICES),
        help="both (the bricks split between the arms, as the seed's), or left or "
        "right building alone (default both)",
    )


def add_physics_args(
    p: argparse.ArgumentParser,
    seed_default: int = 0,
    seed_help: str = "of the spawn jitter (default 0)",
) -> None:
    """One flag per row of the parameter table, then the spawn jitter and the seed."""
    for param in PARAMS:
        p.add_argument(
            param.flag,
            dest=param.name,
            type=number(param.label),
            metavar=param.unit.upper() or "MU",
            default=None,  # the robot's own at its scale (SimConfig.for_robot)
            help=param.help,
        )
    p.add_argument(
        "--spawn-jitter",
        type=number("spawn jitter"),
        default=0.0,
        metavar="MM",
        help="each spawned brick lands up to MM off the spot in x and y; accepted "
        f"{SPAWN_JITTER_MM.text} (default 0)",
    )
    p.add_argument("--seed", type=whole("seed"), default=seed_default, help=seed_help)


def add_backend_args(p: argparse.ArgumentParser, what: str) -> None:
    """--backend and --ray-address: where the `what` (builds, episodes) run."""
    p.add_argument(
        "--backend",
        type=one_of("backend", BACKENDS),
        default="process",
        metavar="|".join(BACKENDS),
        help=f"process (the {what} in worker processes on this machine, default) or ray",
    )
    p.add_argument(
        "--ray-address",
        help="with --backend ray: an existing Ray cluster (default: start one here)",
    )


def add_out_args(p: argparse.ArgumentParser, default: Path) -> None:
    """--out and --quiet, as build and sweep share them."""
    p.add_argument(
        "--out",
        type=output_path("out", folder=True),
        default=default,
        metavar="DIR",
        help=f"output folder, held by this run while it runs (default {default})",
    )
    p.add_argument(
        "--quiet",
        action="store_true",
        help="no progress report on stderr (default: one, a bar on a terminal, a few "
        "lines elsewhere)",
    )


def config_from_args(args: argparse.Namespace) -> SimConfig:
    """The run's settings; ConfigError if a value is out of range."""
    from dataclasses import replace

    config = SimConfig.for_robot(args.robot)  # its scale: brick, table, spot, grip
    for param in PARAMS:
        value = getattr(args, param.name)
        if value is not None:
            config = param.apply(config, value)
    layout = replace(config.layout, spawn_jitter_mm=args.spawn_jitter)
    return replace(
        config,
        layout=layout,
        seed=args.seed,
        schedule=getattr(args, "schedule", SCHEDULES[0]),
    )


def size_options(args: argparse.Namespace) -> dict[str, int]:
    """The structure's size options given (by their keywords: `--wall-width` is `width`)."""
    given = {
        option: getattr(args, flag[2:].replace("-", "_"))
        for option, (flag, _) in SIZE_FLAGS.items()
    }
    return {option: value for option, value in given.items() if value is not None}


def spec_from_args(args: argparse.Namespace, config: SimConfig) -> StructureSpec:
    """The structure and its size; ConfigError for a bad size, option or goals file."""
    goals = None
    if args.goals is not None:
        from ..core.goals import load_goals

        table_z = config.layout.table_top_z + config.brick.height / 2
        goals = load_goals(args.goals, config.brick, table_z)
    return StructureSpec(
        args.structure,
        **size_options(args),
        goals=goals,
        goals_source=args.goals.name if args.goals else "",
    )
