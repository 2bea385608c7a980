"""The command line's arguments: generated from the parameter table (physics flags, sweep axes)
and the structure catalogue (size options and their defaults), then turned into settings.

Ranges are checked by the settings classes, not here, so a value is accepted or refused for
the same reason whichever way it arrives.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import Callable, NoReturn, Sequence

from ..choices import ARM_CHOICES, CAMERAS, SCHEDULES
from ..config import SimConfig, VideoConfig
from ..core.structures import (
    MAX_BRICKS,
    MAX_COURSE,
    MAX_LAYERS,
    STRUCTURES,
    StructureSpec,
)
from ..errors import ConfigError
from ..params import PARAMS
from ..robots import DEFAULT_ROBOT, PRESETS
from ..sweep.grid import SweepConfig, parse_axis

EXIT_FAILED = 1
EXIT_USAGE = 2
SWEEP_JITTER_MM = 2.0  # a sweep's spawned bricks land up to this far off the spot by default

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
            return float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name}: {text!r} is not a number") from None

    return parse


def whole(name: str, accepted: str = "") -> Callable[[str], int]:
    """Text to int; the range is checked where the value is used (settings, StructureSpec)."""

    def parse(text: str) -> int:
        try:
            return int(text)
        except ValueError:
            hint = f"; accepted {accepted}" if accepted else ""
            raise argparse.ArgumentTypeError(f"{name}: {text!r} is not a whole number{hint}") from None

    return parse


def one_of(name: str, options: Sequence[str]) -> Callable[[str], str]:
    def parse(text: str) -> str:
        if text not in options:
            raise argparse.ArgumentTypeError(f"{name}: unknown {text!r}; accepted {', '.join(options)}")
        return text

    return parse


def _size_help(option: str) -> str:
    users = [f"{n} ({d[option]})" for n, (_, d) in STRUCTURES.items() if option in d]
    return f"{', '.join(users)}; accepted {SIZE_FLAGS[option][1]} (defaults in brackets)"


def add_robot_arg(p: argparse.ArgumentParser) -> None:
    p.add_argument("--robot", type=one_of("robot", tuple(PRESETS)), default=DEFAULT_ROBOT,
                   metavar="|".join(PRESETS),
                   help=f"{', '.join(f'{n} ({r.summary})' for n, r in PRESETS.items())}; "
                        f"default {DEFAULT_ROBOT}")


def add_schedule_arg(p: argparse.ArgumentParser) -> None:
    p.add_argument("--schedule", type=one_of("schedule", SCHEDULES), default=SCHEDULES[0],
                   metavar="|".join(SCHEDULES),
                   help="lockstep: the seed's four phases (default); overlap: each arm carries "
                        "its brick straight to its place, the arms taking turns in the zone")


def add_structure_args(p: argparse.ArgumentParser) -> None:
    add_robot_arg(p)
    names = sorted(STRUCTURES)
    p.add_argument("--structure", type=one_of("structure", names), default="pyramid-even",
                   metavar="NAME", help=f"{', '.join(names)} (default pyramid-even)")
    for option, (flag, accepted) in SIZE_FLAGS.items():
        p.add_argument(flag, metavar="N", type=whole(flag[2:].replace("-", " "), accepted),
                       help=_size_help(option))
    p.add_argument("--goals", type=Path, metavar="FILE",
                   help="list: place goals, JSON or CSV of x, y, z, yaw (examples in "
                        "pyramid_sim/assets/goals/)")
    p.add_argument("--arms", type=one_of("arms", ARM_CHOICES), default="both",
                   metavar="|".join(ARM_CHOICES),
                   help="both (the bricks split between the arms, as the seed's), or left or "
                        "right building alone (default both)")


def add_physics_args(p: argparse.ArgumentParser) -> None:
    """One flag per row of the parameter table, then the spawn jitter and its seed."""
    for param in PARAMS:
        p.add_argument(param.flag, dest=param.name, type=number(param.label),
                       metavar=param.unit.upper() or "MU", default=param.default, help=param.help)
    p.add_argument("--spawn-jitter", type=number("spawn jitter"), default=0.0, metavar="MM",
                   help="each spawned brick lands up to MM off the spot in x and y; accepted "
                        "[0, 10] (default 0)")
    p.add_argument("--seed", type=whole("seed"), default=0, help="of the spawn jitter (default 0)")


def add_sweep_axes(p: argparse.ArgumentParser) -> None:
    """One grid flag per row of the parameter table."""
    for param in PARAMS:
        p.add_argument(param.flag, dest=param.name, metavar="GRID",
                       help=f"{param.label}, start:stop:count or a,b,c; accepted values "
                            f"{param.range_text} (default {param.default:g})")


# dest -> (flag, what it sets: the film alone or the film and the still, VideoConfig field)
VIDEO_OPTIONS = {
    "fps": ("--fps", "film", "fps"), "speedup": ("--speedup", "film", "speedup"),
    "video_width": ("--video-width", "both", "width"),
    "video_height": ("--video-height", "both", "height"),
    "camera": ("--camera", "both", "camera"), "shadows": ("--shadows", "both", "shadows"),
    "antialias": ("--antialias", "both", "antialias"),
}


def renamed(new: str, note: str) -> type[argparse.Action]:
    """A flag that is no more: refused in one line giving its new name, with or without a
    value after it."""

    class Renamed(argparse.Action):
        def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace,
                     values: object, option_string: str | None = None) -> None:
            parser.error(f"{option_string} is now {new} ({note})")

    return Renamed


def add_video_args(p: argparse.ArgumentParser) -> None:
    """The film's and the still's flags. Their defaults are None here (the help text names the
    real ones) so a setting given without --video or --snapshot can be told and refused."""
    d = VideoConfig()
    p.add_argument("--video", type=Path, metavar="PATH.mp4",
                   help="render the build to this MP4 (H.264)")
    p.add_argument("--snapshot", type=Path, metavar="PATH.png",
                   help="write a PNG of the final structure")
    p.add_argument("--fps", type=whole("fps"),
                   help=f"video frames a second, 1 to 120 (default {d.fps})")
    p.add_argument("--video-width", type=whole("video width"), metavar="PIXELS",
                   help=f"of the video and the snapshot, even, 16 to 1920 (default {d.width})")
    p.add_argument("--video-height", type=whole("video height"), metavar="PIXELS",
                   help=f"of the video and the snapshot, even, 16 to 1080 (default {d.height})")
    p.add_argument("--width", nargs="?", help=argparse.SUPPRESS, action=renamed(
        "--video-width", "the video's width in pixels; a wall's course width is --wall-width"))
    p.add_argument("--height", nargs="?", help=argparse.SUPPRESS, action=renamed(
        "--video-height", "the video's height in pixels"))
    p.add_argument("--camera", type=one_of("camera", CAMERAS), metavar="|".join(CAMERAS),
                   help=f"{', '.join(CAMERAS[:-1])} or {CAMERAS[-1]} (default {d.camera})")
    p.add_argument("--shadows", action=argparse.BooleanOptionalAction,
                   help="render shadows, about 4x the render cost (default off)")
    p.add_argument("--speedup", type=number("speedup"), metavar="K",
                   help="simulated seconds a second of video: one frame every K/fps simulated "
                        f"seconds, so K=4 makes a 4-minute build a 1-minute film; [0.1, 100] "
                        f"(default {d.speedup:g})")
    p.add_argument("--antialias", type=whole("antialias"), metavar="SAMPLES",
                   help=f"multisample anti-aliasing: 0, 2, 4 or 8, 4 costing ~1.7x (default "
                        f"{d.antialias})")


def add_out_args(p: argparse.ArgumentParser, default: Path) -> None:
    """--out and --quiet, as build and sweep share them."""
    p.add_argument("--out", type=Path, default=default, metavar="DIR",
                   help=f"output folder, held by this run while it runs (default {default})")
    p.add_argument("--quiet", action="store_true",
                   help="no progress report on stderr (default: one, a bar on a terminal, a few "
                        "lines elsewhere)")


def add_sweep_args(p: argparse.ArgumentParser) -> None:
    add_sweep_axes(p)
    add_schedule_arg(p)
    add_structure_args(p)
    p.add_argument("--repeats", type=whole("repeats"), default=1,
                   help="runs a point, seeds 0, 1, ... of the spawn jitter (1 to 100, default 1)")
    p.add_argument("--spawn-jitter", type=number("spawn jitter"), default=SWEEP_JITTER_MM,
                   metavar="MM", help=f"spawned bricks land up to MM off the spot, [0, 10] "
                                      f"(default {SWEEP_JITTER_MM:g})")
    p.add_argument("--workers", type=whole("workers"), default=os.cpu_count() or 1,
                   help="runs at once (default: the CPU count)")
    p.add_argument("--timeout", type=number("timeout"), default=900.0,
                   help="seconds a run may take before it is stopped and failed (default 900)")
    p.add_argument("--backend", type=one_of("backend", ("process", "ray")), default="process",
                   metavar="process|ray",
                   help="process (worker processes on this machine, default) or ray")
    p.add_argument("--ray-address", help="with --backend ray: an existing Ray cluster (default: "
                   "start one here)")
    add_out_args(p, Path("runs/sweep"))


def config_from_args(args: argparse.Namespace) -> SimConfig:
    """The run's settings; ConfigError if a value is out of range."""
    from dataclasses import replace

    config = SimConfig()
    for param in PARAMS:
        config = param.apply(config, getattr(args, param.name))
    layout = replace(config.layout, spawn_jitter_mm=args.spawn_jitter)
    return replace(config, layout=layout, seed=args.seed, robot=args.robot,
                   schedule=getattr(args, "schedule", SCHEDULES[0]))


def spec_from_args(args: argparse.Namespace, config: SimConfig) -> StructureSpec:
    """The structure and its size; ConfigError for a bad size, option or goals file."""
    goals = None
    if args.goals is not None:
        from ..core.goals import load_goals

        table_z = config.layout.table_top_z + config.brick.height / 2
        goals = load_goals(args.goals, config.brick, table_z)
    sizes = {option: getattr(args, flag[2:].replace("-", "_")) for option, (flag, _) in SIZE_FLAGS.items()}
    return StructureSpec(
        args.structure, **sizes, goals=goals, goals_source=args.goals.name if args.goals else ""
    )


def video_config_from_args(args: argparse.Namespace) -> VideoConfig:
    """The film's and the still's settings, the defaults where none is given; ConfigError for
    one out of range or given without the output it sets."""
    refuse_idle_video_options(args)
    given = {field: getattr(args, dest) for dest, (_, _, field) in VIDEO_OPTIONS.items()}
    return VideoConfig(**{field: value for field, value in given.items() if value is not None})


def refuse_idle_video_options(args: argparse.Namespace) -> None:
    """ConfigError for a video setting given without --video (or --snapshot, for those that
    set the still too): ignored, it would let the user believe it did something."""
    for dest, (flag, needs, _) in VIDEO_OPTIONS.items():
        if getattr(args, dest) is None:
            continue
        if needs == "film" and args.video is None:
            raise ConfigError(f"{flag}: a setting of the video, but no --video is given; "
                              "accepted with --video PATH.mp4")
        if args.video is None and args.snapshot is None:
            raise ConfigError(f"{flag}: a setting of the video and the snapshot, but neither "
                              "--video nor --snapshot is given; accepted with --video PATH.mp4 "
                              "or --snapshot PATH.png")


def sweep_config_from_args(args: argparse.Namespace) -> SweepConfig:
    """The sweep's grid and settings; ConfigError for a bad grid or option."""
    axes = tuple(
        parse_axis(p.name, getattr(args, p.name)) for p in PARAMS if getattr(args, p.name) is not None
    )
    return SweepConfig(
        axes=axes, structure=spec_from_args(args, SimConfig()), arms=args.arms, repeats=args.repeats,
        robot=args.robot, schedule=args.schedule,
        spawn_jitter_mm=args.spawn_jitter, workers=args.workers, timeout=args.timeout,
        backend=args.backend, ray_address=args.ray_address,
    )
