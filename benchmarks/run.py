#!/usr/bin/env python3
"""Benchmark: bare physics, the headless build, IK, rendering and sweeps, in one run.

    python benchmarks/run.py [--json PATH] [--layers N] [--robot NAME] [--frames N]
                             [--sweep-builds N] [--sweep-rounds N]

Prints a table of every figure against its target; `--json` also writes the figures.
Targets are reported, never asserted: these machines are too noisy for timed tests.
"""

from __future__ import annotations

import sys

from pyramid_sim.cli.args import EXIT_USAGE, Parser, one_of, output_path, whole
from pyramid_sim.errors import ConfigError
from pyramid_sim.output.files import check_writable_dir, write_json_atomic
from pyramid_sim.output.gl_backend import choose_gl_backend
from pyramid_sim.robots import DEFAULT_ROBOT, PRESETS


def build_parser() -> Parser:
    """The script's flags."""
    parser = Parser(prog="benchmarks/run.py", description=__doc__.splitlines()[0])
    parser.add_argument(
        "--json",
        type=output_path("json path", folder=False),
        metavar="PATH",
        help="also write the figures here",
    )
    parser.add_argument(
        "--layers",
        type=whole("layers", "1 to 5"),
        default=4,
        help="pyramid-even size built (default 4: 20 bricks)",
    )
    parser.add_argument(
        "--robot",
        type=one_of("robot", tuple(PRESETS)),
        default=DEFAULT_ROBOT,
        help=f"a robot preset: {', '.join(PRESETS)} (default {DEFAULT_ROBOT})",
    )
    parser.add_argument(
        "--frames",
        type=whole("frames", "1 to 10000"),
        default=60,
        help="frames rendered per setting (default 60)",
    )
    parser.add_argument(
        "--sweep-builds",
        type=whole("sweep builds", "1 to 100"),
        default=2,
        help="builds per worker in the sweep figures (default 2)",
    )
    parser.add_argument(
        "--sweep-rounds",
        type=whole("sweep rounds", "1 to 10"),
        default=2,
        help="alternated 1- and 2-worker sweeps, best of each (default 2)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        choose_gl_backend()  # before mujoco is imported
        from pyramid_sim.perf.figures import BenchConfig, run_all
        from pyramid_sim.perf.targets import table

        bench = BenchConfig(
            layers=args.layers,
            robot=args.robot,
            frames=args.frames,
            sweep_builds=args.sweep_builds,
            sweep_rounds=args.sweep_rounds,
        )
        if args.json is not None:
            check_writable_dir(args.json.parent)
    except ConfigError as err:
        print(f"benchmarks/run.py: error: {err}", file=sys.stderr)
        return EXIT_USAGE
    figures = run_all(bench, progress=lambda what: print(f"measuring: {what}", file=sys.stderr))
    print(table(figures))
    if args.json is not None:
        write_json_atomic(args.json, figures)
    return 0


if __name__ == "__main__":
    sys.exit(main())
