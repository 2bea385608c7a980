"""`pyramid-sim`: plan and build brick structures with two simulated Pandas.

Thin: parses arguments into configuration values (which validate themselves), calls the library,
prints. Every bad input ends in one line on stderr and exit status 2, before anything is written.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
import tempfile
import threading
from dataclasses import replace
from pathlib import Path
from typing import NoReturn, Sequence

from .config import BrickConfig, GripperConfig, SimConfig, VideoConfig
from .errors import ConfigError, PyramidSimError
from .core.plan import ARM_CHOICES
from .core.structures import MAX_BRICKS, MAX_COURSE, MAX_LAYERS, STRUCTURES, StructureSpec
from .sweep.grid import PARAMETERS, SweepConfig, parse_axis

EXIT_FAILED = 1
EXIT_USAGE = 2


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one line, no usage block
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")


def _number(name: str):
    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name}: {text!r} is not a number") from None
        return value  # ranges (and NaN, inf) are checked by the configuration classes

    return parse


def _one_of(name: str, options: Sequence[str]):
    def parse(text: str) -> str:
        if text not in options:
            raise argparse.ArgumentTypeError(
                f"{name}: unknown {text!r}; accepted {', '.join(options)}"
            )
        return text

    return parse


def _add_structure_args(p: argparse.ArgumentParser) -> None:
    names = sorted(STRUCTURES)
    p.add_argument("--structure", type=_one_of("structure", names), default="pyramid-even",
                   metavar="NAME", help=f"{', '.join(names)} (default pyramid-even)")
    p.add_argument("--layers", type=_whole("layers", f"1 to {MAX_LAYERS}"), metavar="N",
                   help="pyramid, pyramid-even (default 4), wall-pyramid (3), towers (3)")
    p.add_argument("--bricks", type=_whole("bricks", f"1 to {MAX_BRICKS}"), metavar="N",
                   help="wall: bricks in all (default 15)")
    # Not --width: that is the video's width in `build` (issue 3's interface, kept).
    p.add_argument("--wall-width", dest="wall_width", metavar="N",
                   type=_whole("wall width", f"1 to {MAX_COURSE}"), help="wall, wall-pyramid: bricks a course (default 5)")
    p.add_argument("--towers", type=_whole("towers", f"1 to {MAX_COURSE}"), metavar="N",
                   help="towers: how many (default 4)")
    p.add_argument("--goals", type=Path, metavar="FILE",
                   help="list: place goals, JSON or CSV of x, y, z, yaw (assets/goals/)")
    p.add_argument("--arms", type=_one_of("arms", ARM_CHOICES), default="both",
                   help="both (the seed's lockstep) or one arm building alone")


def _add_physics_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("--friction", type=_number("friction"), default=BrickConfig.friction,
                   help="brick friction coefficient (0, 5]")
    p.add_argument("--brick-mass", type=_number("brick mass"), default=BrickConfig.mass,
                   help="kg, (0, 5]")
    p.add_argument("--grip-force", type=_number("grip force"), default=GripperConfig.force,
                   help="N per finger pad, (0, 140]")
    p.add_argument("--pad-friction", type=_number("pad friction"),
                   default=GripperConfig.pad_friction, help="finger pad friction coefficient (0, 5]")
    p.add_argument("--spawn-jitter", type=_number("spawn jitter"), default=0.0, metavar="MM",
                   help="each spawned brick lands up to MM off the spot in x and y, [0, 10]")
    p.add_argument("--seed", type=_whole("seed"), default=0, help="of the spawn jitter")


def spec_from_args(args: argparse.Namespace, config: SimConfig) -> StructureSpec:
    """The structure and its size; ConfigError for a bad size, option or goals file."""
    goals = None
    if args.goals is not None:
        from .core.goals import load_goals

        table_z = config.layout.table_top_z + config.brick.height / 2
        goals = load_goals(args.goals, config.brick, table_z)
    return StructureSpec(
        args.structure, layers=args.layers, bricks=args.bricks, width=args.wall_width,
        towers=args.towers, goals=goals, goals_source=args.goals.name if args.goals else "",
    )


def make_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="pyramid-sim", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    plan = sub.add_parser("plan", help="print the build plan as JSON, without simulating")
    _add_structure_args(plan)
    _add_physics_args(plan)
    build = sub.add_parser("build", help="simulate the build headless and write DIR/result.json")
    _add_structure_args(build)
    _add_physics_args(build)
    build.add_argument("--out", type=Path, default=Path("runs/latest"), help="output folder")
    build.add_argument("--quiet", action="store_true", help="no progress bars")
    _add_video_args(build)
    view = sub.add_parser("view", help="watch the build live in MuJoCo's viewer (needs a display)")
    _add_structure_args(view)
    _add_physics_args(view)
    _add_sweep_parser(sub)
    reach = sub.add_parser("reach", help="the largest size of each structure within reach, by IK")
    reach.add_argument("--arms", type=_one_of("arms", (*ARM_CHOICES, "all")), default="all",
                       help="which arm set to check (default all three)")
    return parser


def _add_sweep_parser(sub: argparse._SubParsersAction) -> None:
    sweep = sub.add_parser(
        "sweep", help="build at every point of a parameter grid; writes DIR/sweep.csv and sweep.png"
    )
    spec = "start:stop:count or a,b,c"
    sweep.add_argument("--friction", metavar="GRID", help=f"brick friction, {spec}")
    sweep.add_argument("--brick-mass", metavar="GRID", help=f"brick mass (kg), {spec}")
    sweep.add_argument("--grip-force", metavar="GRID", help=f"grip force (N), {spec}")
    sweep.add_argument("--pad-friction", metavar="GRID", help=f"finger pad friction, {spec}")
    _add_structure_args(sweep)
    sweep.add_argument("--repeats", type=_whole("repeats"), default=1,
                       help="runs a point, seeds 0, 1, ... of the spawn jitter (1 to 100)")
    sweep.add_argument("--spawn-jitter", type=_number("spawn jitter"), default=2.0, metavar="MM",
                       help="spawned bricks land up to MM off the spot, [0, 10] (default 2)")
    sweep.add_argument("--workers", type=_whole("workers"), default=os.cpu_count() or 1,
                       help="runs at once (default: the CPU count)")
    sweep.add_argument("--timeout", type=_number("timeout"), default=900.0,
                       help="seconds a run may take before it is stopped and failed (default 900)")
    sweep.add_argument("--backend", type=_one_of("backend", ("process", "ray")), default="process")
    sweep.add_argument("--ray-address", help="an existing Ray cluster (default: start one here)")
    sweep.add_argument("--out", type=Path, default=Path("runs/sweep"), help="output folder")
    sweep.add_argument("--quiet", action="store_true", help="no progress bar")


def _add_video_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("--video", type=Path, help="render the build to this MP4 (H.264)")
    p.add_argument("--snapshot", type=Path, help="write a PNG of the final structure")
    p.add_argument("--fps", type=_whole("fps"), default=30, help="video frame rate, 1 to 120")
    p.add_argument("--width", type=_whole("width"), default=640, help="pixels, even, 16 to 1920")
    p.add_argument("--height", type=_whole("height"), default=480, help="pixels, even, 16 to 1080")
    p.add_argument("--camera", default="overview", help="overview, front or top")
    p.add_argument("--shadows", action=argparse.BooleanOptionalAction, default=False,
                   help="render shadows (about 4x the render cost)")
    p.add_argument("--antialias", type=_whole("antialias"), default=0, metavar="SAMPLES",
                   help="multisample anti-aliasing: 0 (default), 2, 4 or 8 (4 costs ~1.7x)")


def _whole(name: str, accepted: str = ""):
    """Text to int; the range is checked where the value is used (config, StructureSpec)."""

    def parse(text: str) -> int:
        try:
            return int(text)
        except ValueError:
            hint = f"; accepted {accepted}" if accepted else ""
            raise argparse.ArgumentTypeError(f"{name}: {text!r} is not a whole number{hint}") from None

    return parse


def config_from_args(args: argparse.Namespace) -> SimConfig:
    """The run's configuration; ConfigError if a value is out of range."""
    base = SimConfig()
    brick = replace(base.brick, friction=args.friction, mass=args.brick_mass)
    gripper = replace(base.gripper, force=args.grip_force, pad_friction=args.pad_friction)
    layout = replace(base.layout, spawn_jitter_mm=args.spawn_jitter)
    return replace(base, brick=brick, gripper=gripper, layout=layout, seed=args.seed)


def check_writable_dir(path: Path) -> None:
    """ConfigError unless `path` is, or can be made, a writable folder (nothing is created)."""
    probe = path
    while not probe.exists():
        probe = probe.parent
    if not probe.is_dir():
        raise ConfigError(f"out: {str(probe)!r} is not a folder")
    try:
        with tempfile.TemporaryFile(dir=probe):
            pass
    except OSError as err:
        raise ConfigError(f"out: {str(probe)!r} is not writable ({err.strerror})") from None


def _cmd_plan(args: argparse.Namespace) -> int:
    from .core.plan import make_plan

    config = config_from_args(args)
    plan = make_plan(spec_from_args(args, config), config, args.arms)
    print(json.dumps(plan.to_json(), indent=2))
    return 0


def _cmd_build(args: argparse.Namespace) -> int:
    config = config_from_args(args)
    video_config = VideoConfig(
        args.fps, args.width, args.height, args.camera, args.shadows, args.antialias
    )
    check_writable_dir(args.out)
    for path, suffix in ((args.video, ".mp4"), (args.snapshot, ".png")):
        if path is not None:
            if path.suffix.lower() != suffix:
                raise ConfigError(f"{suffix[1:]} path: {str(path)!r} must end in {suffix}")
            check_writable_dir(path.parent)
    if args.video is not None or args.snapshot is not None:
        from .output.gl_backend import choose_gl_backend

        choose_gl_backend()  # before mujoco is imported
    from tqdm import tqdm

    from .physics.build import prepare, run_build
    from .output.results import write_json_atomic

    plan = prepare(spec_from_args(args, config), config, args.arms)
    video = (video_config, args.video) if args.video is not None else None
    snapshot = (video_config, args.snapshot) if args.snapshot is not None else None
    with (
        tqdm(total=len(plan.bricks), unit="brick", disable=args.quiet, desc="bricks") as bar,
        tqdm(unit="frame", disable=args.quiet or video is None, desc="frames", position=1) as frames,
    ):
        document = run_build(
            plan, config, on_placed=lambda n: bar.update(1), video=video,
            on_frame=lambda n: frames.update(1), snapshot=snapshot,
        )
    write_json_atomic(args.out / "result.json", document)
    worst = document["worst_error_xy_mm"]
    print(
        f"{document['bricks_placed']}/{document['bricks_total']} bricks in place, worst xy "
        f"error {'(a brick not placed)' if worst is None else f'{worst:.2f} mm'}, max slip "
        f"{document['max_slip_mm']} mm, {document['sim_s_per_brick']} sim s/brick, "
        f"{document['real_time_factor']}x real time, {document['drops']} drops -> "
        f"{args.out / 'result.json'}"
    )
    if not document["success"]:
        print(f"build failed: {document['failure_reason']}", file=sys.stderr)
        return EXIT_FAILED
    return 0


def _cmd_view(args: argparse.Namespace) -> int:
    import time

    import mujoco.viewer

    from .physics.build import prepare
    from .physics.loop import BuildSim

    config = config_from_args(args)
    sim = BuildSim(prepare(spec_from_args(args, config), config, args.arms), config)
    start = time.perf_counter()
    try:
        viewer = mujoco.viewer.launch_passive(sim.model, sim.data)
    except Exception as err:  # no display, no GLFW
        raise ConfigError(f"view: cannot open a window ({err}); use build --video instead") from None

    def show(model: mujoco.MjModel, data: mujoco.MjData) -> None:
        ahead = data.time - (time.perf_counter() - start)
        if ahead > 0:
            time.sleep(ahead)  # real-time speed
        viewer.sync()

    with viewer:
        sim.run(observer=show, observe_dt=1.0 / 60.0)
    return 0


def sweep_config_from_args(args: argparse.Namespace) -> SweepConfig:
    """The sweep's grid and settings; ConfigError for a bad grid or option."""
    axes = tuple(
        parse_axis(name, getattr(args, name)) for name in PARAMETERS if getattr(args, name) is not None
    )
    return SweepConfig(
        axes=axes, structure=spec_from_args(args, SimConfig()), arms=args.arms, repeats=args.repeats,
        spawn_jitter_mm=args.spawn_jitter, workers=args.workers, timeout=args.timeout,
        backend=args.backend, ray_address=args.ray_address,
    )


def _cmd_sweep(args: argparse.Namespace) -> int:
    config = sweep_config_from_args(args)
    check_writable_dir(args.out)
    if config.backend == "ray":
        from .sweep.runner import require_ray

        require_ray()
    from tqdm import tqdm

    from .physics.build import prepare
    from .sweep.run import report, run_sweep

    prepare(config.structure, SimConfig(), config.arms)  # out of reach: one line, nothing run
    runs = len(config.runs())
    with tqdm(total=runs, unit="build", disable=args.quiet, desc="sweep") as bar:
        rows, ran = run_sweep(
            config, args.out, on_row=lambda result: bar.update(1), on_skip=bar.update
        )
    print(report(rows, config, args.out))
    ok = sum(r["success"] == "true" for r in rows)
    print(
        f"{ok}/{len(rows)} builds succeeded ({ran} run now, {runs - ran} already in the CSV) -> "
        f"{args.out / 'sweep.csv'}, {args.out / 'sweep.png'}"
    )
    return 0 if len(rows) == runs else EXIT_FAILED


def _cmd_reach(args: argparse.Namespace) -> int:
    from .physics.reach import ReachChecker, held_fixed
    from .core.structures import SIZE_KNOB

    arm_sets = ("both", "left", "right") if args.arms == "all" else (args.arms,)
    checker = ReachChecker(SimConfig())
    arm_heads = [f"{a} arm{'s' if a == 'both' else ''}" for a in arm_sets]
    rows = [["structure", "grows", "other options", *arm_heads]]
    for name, knob in SIZE_KNOB.items():
        spec = StructureSpec(name)
        largest = [str(checker.largest(spec, a)) for a in arm_sets]
        rows.append([name, knob, held_fixed(spec), *largest])
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    for r in rows:
        print("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip())
    return 0


COMMANDS = {
    "plan": _cmd_plan, "build": _cmd_build, "view": _cmd_view, "sweep": _cmd_sweep,
    "reach": _cmd_reach,
}


def _exit_on_sigterm(signum: int, frame: object) -> NoReturn:
    raise SystemExit(128 + signum)


def main(argv: Sequence[str] | None = None) -> int:
    # A terminated run unwinds like Ctrl-C, so the video's temporary file is removed: by
    # default SIGTERM ends Python without running any `finally`.
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, _exit_on_sigterm)
    parser = make_parser()
    args = parser.parse_args(argv)
    try:
        return COMMANDS[args.command](args)
    except ConfigError as err:
        print(f"pyramid-sim: error: {err}", file=sys.stderr)
        return EXIT_USAGE
    except (PyramidSimError, OSError) as err:
        print(f"pyramid-sim: failed: {err}", file=sys.stderr)
        return EXIT_FAILED


if __name__ == "__main__":
    sys.exit(main())
