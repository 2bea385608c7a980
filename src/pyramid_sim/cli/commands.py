"""What each `pyramid-sim` command does: settings from its arguments, the library, a summary.

Physics is imported only after every argument has been checked, so a refusal costs nothing.
"""

from __future__ import annotations

import argparse
import json
import sys

from ..config import SimConfig
from ..errors import ConfigError
from ..output.files import check_writable_dir, removed_if_failed, write_json_atomic
from .args import (
    EXIT_FAILED,
    config_from_args,
    spec_from_args,
    sweep_config_from_args,
    video_config_from_args,
)


def cmd_plan(args: argparse.Namespace) -> int:
    """The plan as JSON, its every pose checked by IK first: a plan `build` would refuse is
    refused here too."""
    config = config_from_args(args)
    spec = spec_from_args(args, config)
    from ..physics.build import prepare

    plan = prepare(spec, config, args.arms)
    print(json.dumps(plan.to_json(), indent=2))
    return 0


def _check_outputs(args: argparse.Namespace) -> None:
    check_writable_dir(args.out)
    for path, suffix in ((args.video, ".mp4"), (args.snapshot, ".png")):
        if path is not None:
            if path.suffix.lower() != suffix:
                raise ConfigError(f"{suffix[1:]} path: {str(path)!r} must end in {suffix}")
            check_writable_dir(path.parent, f"{suffix[1:]} path")


def cmd_build(args: argparse.Namespace) -> int:
    config = config_from_args(args)
    video_config = video_config_from_args(args)
    spec = spec_from_args(args, config)
    _check_outputs(args)
    if args.video is not None or args.snapshot is not None:
        from ..output.gl_backend import choose_gl_backend

        choose_gl_backend()  # before mujoco is imported
    from tqdm import tqdm

    from ..physics.build import prepare, run_build

    plan = prepare(spec, config, args.arms)
    video = (video_config, args.video) if args.video is not None else None
    snapshot = (video_config, args.snapshot) if args.snapshot is not None else None
    folders = [args.out, *(p.parent for p in (args.video, args.snapshot) if p is not None)]
    with (
        removed_if_failed(folders),
        tqdm(total=len(plan.bricks), unit="brick", disable=args.quiet, desc="bricks") as bar,
        tqdm(unit="frame", disable=args.quiet or video is None, desc="frames", position=1) as frames,
    ):
        def placed(n: int) -> None:
            bar.update(1)
            # The film's length is known only at the end: estimate it from the pace so far.
            frames.total = round(frames.n * len(plan.bricks) / n)
            frames.refresh()

        result = run_build(
            plan, config, on_placed=placed, video=video,
            on_frame=lambda n: frames.update(1), snapshot=snapshot,
        )
        write_json_atomic(args.out / "result.json", result.to_json())
    print(_summary(result, args))
    if not result.success:
        print(f"build failed: {result.failure_reason}", file=sys.stderr)
        return EXIT_FAILED
    return 0


def _summary(result, args: argparse.Namespace) -> str:
    """The one line a build ends with: what was built, how well, and every file written."""
    worst = result.worst_error_xy_mm
    slip = "-" if result.max_slip_mm is None else f"{result.max_slip_mm}"
    files = [str(args.out / "result.json")]
    files += [str(p) for p in (args.video, args.snapshot) if p is not None]
    return (
        f"{result.bricks_placed}/{result.bricks_total} bricks in place, worst xy "
        f"error {'(a brick not placed)' if worst is None else f'{worst:.2f} mm'}, max slip "
        f"{slip} mm, {result.sim_s_per_brick} sim s/brick, "
        f"{result.real_time_factor}x real time, {result.drops} drops -> {', '.join(files)}"
    )


def cmd_view(args: argparse.Namespace) -> int:
    import os
    import time

    if sys.platform.startswith("linux") and not (
        os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    ):
        raise ConfigError("view: no display (DISPLAY is not set); use build --video instead")
    import mujoco.viewer

    from ..physics.build import prepare
    from ..physics.hooks import BuildHooks
    from ..physics.loop import BuildLoop

    config = config_from_args(args)
    loop = BuildLoop(prepare(spec_from_args(args, config), config, args.arms), config)
    start = time.perf_counter()
    try:
        viewer = mujoco.viewer.launch_passive(loop.model, loop.data)
    except Exception as err:  # no display, no GLFW
        raise ConfigError(f"view: cannot open a window ({err}); use build --video instead") from None

    def show(model: mujoco.MjModel, data: mujoco.MjData) -> None:
        ahead = data.time - (time.perf_counter() - start)
        if ahead > 0:
            time.sleep(ahead)  # real-time speed
        viewer.sync()

    with viewer:
        loop.run(BuildHooks(on_frame=show, frame_dt=1.0 / 60.0))
    return 0


def cmd_sweep(args: argparse.Namespace) -> int:
    config = sweep_config_from_args(args)
    check_writable_dir(args.out)
    if config.backend == "ray":
        from ..sweep.runner import require_ray

        require_ray()
    from tqdm import tqdm

    from ..physics.build import prepare
    from ..sweep.run import report, run_sweep

    prepare(config.structure, SimConfig(robot=config.robot), config.arms)  # out of reach: refused
    runs = len(config.runs())
    with tqdm(total=runs, unit="build", disable=args.quiet, desc="sweep") as bar:
        rows, ran = run_sweep(
            config, args.out, on_row=lambda result: bar.update(1), on_skip=bar.update
        )
    table, plot = report(rows, config, args.out)
    print(table)
    ok = sum(r["success"] == "true" for r in rows)
    broken = [r for r in rows if r["failure_reason"].startswith(("crashed", "timeout"))]
    print(
        f"{ok}/{len(rows)} builds succeeded ({ran} run now, {runs - ran} already in the CSV) -> "
        f"{args.out / 'sweep.csv'}, {plot}"
    )
    if broken:
        print(f"sweep incomplete: {len(broken)} of {len(rows)} runs crashed or timed out, so "
              "their points measure nothing (see failure_reason in sweep.csv)", file=sys.stderr)
    return 0 if len(rows) == runs and not broken else EXIT_FAILED


def cmd_scene(args: argparse.Namespace) -> int:
    """The compiled model a build of these options runs, with its bricks parked, to a file."""
    from ..core.plan import make_plan

    config = config_from_args(args)
    plan = make_plan(spec_from_args(args, config), config, args.arms)
    if args.out.suffix.lower() not in (".mjb", ".xml"):
        raise ConfigError(f"out: {str(args.out)!r} must end in .mjb or .xml")
    check_writable_dir(args.out.parent)
    if args.out.suffix.lower() == ".xml":
        from ..output.scene_files import check_mesh_folder

        check_mesh_folder(args.out)
    from ..physics.scene import write_scene

    with removed_if_failed([args.out.parent]):
        model, written = write_scene(config, len(plan.bricks) + config.spare_bricks, args.out)
    files = [str(args.out)] + [f"{p}/ ({len(list(p.iterdir()))} mesh files)" for p in written[1:]]
    print(f"{model.nbody} bodies, {model.ngeom} geoms, {model.nu} actuators, "
          f"{len(plan.bricks) + config.spare_bricks} bricks -> {', '.join(files)}")
    return 0


def cmd_reach(args: argparse.Namespace) -> int:
    from ..core.structures import SIZE_KNOB, StructureSpec
    from ..physics.reach import ReachChecker, held_fixed

    arm_sets = ("both", "left", "right") if args.arms == "all" else (args.arms,)
    checker = ReachChecker(SimConfig(robot=args.robot))
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
