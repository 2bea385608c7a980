"""The sweep's flags: a grid flag per row of the parameter table and the run options, turned
into a SweepConfig."""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from ..config import SPAWN_JITTER_MM, SimConfig
from ..params import PARAMS, REPEATS, SWEEP_WORKERS
from ..sweep.grid import SweepConfig, parse_axis
from .args import (
    add_backend_args,
    add_out_args,
    add_schedule_arg,
    add_structure_args,
    number,
    spec_from_args,
    whole,
)

SWEEP_JITTER_MM = 2.0  # a sweep's spawned bricks land up to this far off the spot by default


def add_sweep_axes(p: argparse.ArgumentParser) -> None:
    """One grid flag per row of the parameter table."""
    for param in PARAMS:
        p.add_argument(
            param.flag,
            dest=param.name,
            metavar="GRID",
            help=f"{param.label}, start:stop:count or a,b,c; accepted values "
            f"{param.range_text} (default {param.default:g})",
        )


def add_sweep_args(p: argparse.ArgumentParser) -> None:
    add_sweep_axes(p)
    add_schedule_arg(p)
    add_structure_args(p)
    p.add_argument(
        "--repeats",
        type=whole("repeats", REPEATS.whole_text),
        default=1,
        help=f"runs a point, seeds 0, 1, ... of the spawn jitter ({REPEATS.whole_text}, default 1)",
    )
    p.add_argument(
        "--spawn-jitter",
        type=number("spawn jitter"),
        default=SWEEP_JITTER_MM,
        metavar="MM",
        help=f"spawned bricks land up to MM off the spot, {SPAWN_JITTER_MM.text} "
        f"(default {SWEEP_JITTER_MM:g})",
    )
    p.add_argument(
        "--workers",
        type=whole("workers", SWEEP_WORKERS.whole_text),
        default=os.cpu_count() or 1,
        help="runs at once (default: the CPU count)",
    )
    p.add_argument(
        "--timeout",
        type=number("timeout"),
        default=900.0,
        help="seconds a run may take before it is stopped and failed (default 900)",
    )
    p.add_argument(
        "--retry-failed",
        action="store_true",
        help="run again the points DIR/sweep.csv holds as crashed or timed out (say with a "
        "larger --timeout); their new rows stand (default: a point in the CSV is not run "
        "again)",
    )
    add_backend_args(p, "builds")
    add_out_args(p, Path("runs/sweep"))


def sweep_config_from_args(args: argparse.Namespace) -> SweepConfig:
    """The sweep's grid and settings; ConfigError for a bad grid or option."""
    axes = tuple(
        parse_axis(p.name, getattr(args, p.name))
        for p in PARAMS
        if getattr(args, p.name) is not None
    )
    return SweepConfig(
        axes=axes,
        structure=spec_from_args(args, SimConfig.for_robot(args.robot)),
        arms=args.arms,
        repeats=args.repeats,
        robot=args.robot,
        schedule=args.schedule,
        spawn_jitter_mm=args.spawn_jitter,
        workers=args.workers,
        timeout=args.timeout,
        backend=args.backend,
        ray_address=args.ray_address,
        retry_failed=args.retry_failed,
    )
