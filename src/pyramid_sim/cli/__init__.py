"""`pyramid-sim`: plan and build brick structures with two simulated robot arms.

Thin: parses arguments into settings (which validate themselves), calls the library, prints.
Every bad input ends in one line on stderr and exit status 2, before anything is written.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path

from ..choices import ARM_CHOICES
from ..version import __version__
from . import args as a
from . import commands
from .endings import ended
from .evaluate_command import add_evaluate_args, cmd_evaluate
from .record_command import add_record_args, cmd_record
from .replay_command import add_replay_args, cmd_replay
from .sweep_args import add_sweep_args
from .targets import add_overwrite_arg
from .video_args import add_video_args

COMMANDS = {
    "plan": commands.cmd_plan,
    "build": commands.cmd_build,
    "view": commands.cmd_view,
    "sweep": commands.cmd_sweep,
    "reach": commands.cmd_reach,
    "scene": commands.cmd_scene,
    "record": cmd_record,
    "evaluate": cmd_evaluate,
    "replay": cmd_replay,
}


def make_parser() -> a.Parser:
    parser = a.Parser(prog="pyramid-sim", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"pyramid-sim {__version__}")
    sub = parser.add_subparsers(dest="command", parser_class=a.Parser, metavar="COMMAND")
    plan = sub.add_parser("plan", help="print the build plan as JSON, without simulating")
    a.add_structure_args(plan)
    a.add_physics_args(plan)
    build = sub.add_parser("build", help="simulate the build headless and write DIR/result.json")
    a.add_structure_args(build)
    a.add_physics_args(build)
    a.add_schedule_arg(build)
    a.add_out_args(build, Path("runs/latest"))
    add_video_args(build)
    add_overwrite_arg(build, "a result.json, film or still")
    view = sub.add_parser("view", help="watch the build live in MuJoCo's viewer (needs a display)")
    a.add_structure_args(view)
    a.add_physics_args(view)
    a.add_schedule_arg(view)
    add_sweep_args(
        sub.add_parser(
            "sweep",
            help="build at every point of a parameter grid; writes DIR/sweep.csv and a plot",
        )
    )
    _add_scene(sub.add_parser("scene", help="write the compiled scene of a build (.mjb or .xml)"))
    add_record_args(
        sub.add_parser("record", help="the expert's builds as a LeRobot dataset (v3.0) in DIR")
    )
    add_evaluate_args(
        sub.add_parser("evaluate", help="score a policy over held-out seeds: DIR/evaluation.json")
    )
    add_replay_args(
        sub.add_parser("replay", help="a run's 3D replay as one HTML page that opens from disk")
    )
    _add_reach(
        sub.add_parser("reach", help="the largest size of each structure within reach, by IK")
    )
    return parser


def _add_scene(scene: a.Parser) -> None:
    """`scene`'s arguments: the build's, and the file the compiled model goes to."""
    a.add_structure_args(scene)
    a.add_physics_args(scene)
    scene.add_argument(
        "--out",
        type=a.output_path("out", folder=False),
        required=True,
        metavar="FILE",
        help="FILE.mjb (MuJoCo's binary model) or FILE.xml (MJCF)",
    )
    add_overwrite_arg(scene, "a FILE")


def _add_reach(reach: a.Parser) -> None:
    """`reach`'s arguments: the robot, the arm set, and whether any layout is checked."""
    a.add_robot_arg(reach)
    arm_sets = (*ARM_CHOICES, "all")
    reach.add_argument(
        "--arms",
        type=a.one_of("arms", arm_sets),
        default="both",
        metavar="|".join(arm_sets),
        help="the arm set to check: both, left, right, or all three (default both, as a build)",
    )
    reach.add_argument(
        "--any-layout",
        action="store_true",
        help="add the column 'both arms, any layout': the largest size within reach wherever "
        "the learning environment's layout variation puts it (checked at its region's 16 "
        "corners: several times the IK work) (default: the arms' columns alone)",
    )


def main(argv: Sequence[str] | None = None) -> int:
    parser = make_parser()
    args = parser.parse_args(argv)
    if args.command is None:  # what to run is missing: the usage, as argparse refuses
        parser.print_help(sys.stderr)
        return a.EXIT_USAGE
    return ended("pyramid-sim", lambda: COMMANDS[args.command](args))


__all__ = ["main", "make_parser"]
