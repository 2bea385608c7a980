"""What each `pyramid-sim` command does: settings from its arguments, the library, a summary.

Physics is imported only after every argument has been checked, so a refusal costs nothing.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path

from ..choices import ARM_CHOICES, ArmChoice
from ..config import SimConfig
from ..core.plan import Plan
from ..errors import ConfigError, MachineError
from ..output.claims import check_file, check_not_dataset
from ..output.files import check_writable_dir, removed_if_failed
from ..output.lock import holding
from ..output.result import BuildResult
from .args import EXIT_FAILED, config_from_args, size_options, spec_from_args
from .progress import Progress
from .sweep_args import sweep_config_from_args
from .targets import check_build_targets
from .video_args import video_config_from_args


def cmd_plan(args: argparse.Namespace) -> int:
    """The plan as JSON, its every pose checked by IK first: a plan `build` would refuse is
    refused here too."""
    config = config_from_args(args)
    spec = spec_from_args(args, config)
    from ..physics.reach import prepare

    plan = prepare(spec, config, args.arms)
    print(json.dumps(plan.to_dict(), indent=2))
    return 0


def cmd_build(args: argparse.Namespace) -> int:
    """Simulate one build through `pyramid_sim.build`, into its held folders; exit 0 iff
    result.json says it succeeded."""
    import pyramid_sim

    config = config_from_args(args)
    video_config = video_config_from_args(args)
    with Progress(
        "bricks",
        0,  # the plan's bricks, once it is made
        "brick",
        quiet=args.quiet,
        count_unit="frame" if args.video is not None else None,
    ) as progress:
        result = pyramid_sim.build(
            args.structure,
            arms=args.arms,
            config=config,
            video=args.video,
            snapshot=args.snapshot,
            video_config=video_config,
            out=args.out,
            on_start=lambda plan: started(args, plan, config, progress),
            on_placed=progress.advance_to,
            on_frame=lambda n: progress.count(),
            goals=args.goals,
            **size_options(args),
        )
    files = [args.out / "result.json", *(p for p in (args.video, args.snapshot) if p is not None)]
    print(build_summary(result, files))
    return 0 if result.success else EXIT_FAILED


def started(args: argparse.Namespace, plan: Plan, config: SimConfig, progress: Progress) -> None:
    """The plan is checked and the folders held: what the build would write over is judged
    (before any physics), then the progress starts."""
    check_build_targets(args, plan, config)
    progress.start(total=len(plan.bricks))


def verdict(result: BuildResult) -> str:
    """`built`, or `failed (why)` with result.json's own failure_reason: the summary opens with
    the same judgement the file and the exit status carry, so they cannot disagree."""
    if result.success:
        return "built"
    return f"failed ({' '.join((result.failure_reason or 'no reason given').split())})"


def build_summary(result: BuildResult, files: Sequence[Path]) -> str:
    """The one line a build ends with: the verdict, what was built, how well, and every file
    written."""
    worst = result.worst_error_xy_mm
    slip = "n/a" if result.max_slip_mm is None else f"{result.max_slip_mm} mm"
    per_brick = "n/a" if result.sim_s_per_brick is None else f"{result.sim_s_per_brick}"
    pace = "n/a" if result.real_time_factor is None else f"{result.real_time_factor}x"
    return (
        f"{verdict(result)}: {result.bricks_placed}/{result.bricks_total} bricks in place, "
        f"worst xy error {'(a brick not placed)' if worst is None else f'{worst:.2f} mm'}, "
        f"max slip {slip}, {per_brick} sim s/brick, {pace} real time, {result.drops} drops "
        f"-> {', '.join(str(f) for f in files)}"
    )


def cmd_view(args: argparse.Namespace) -> int:
    import os
    import time

    if sys.platform.startswith("linux") and not (
        os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    ):
        raise MachineError("view: no display (DISPLAY is not set); use build --video instead")
    import mujoco.viewer

    from ..physics.hooks import BuildHooks
    from ..physics.loop import BuildLoop
    from ..physics.reach import prepare

    config = config_from_args(args)
    loop = BuildLoop.of(prepare(spec_from_args(args, config), config, args.arms), config)
    start = time.perf_counter()
    try:
        viewer = mujoco.viewer.launch_passive(loop.model, loop.data)
    except Exception as err:  # no display, no GLFW
        raise MachineError(
            f"view: cannot open a window ({err}); use build --video instead"
        ) from None

    def show(model: mujoco.MjModel, data: mujoco.MjData) -> None:
        ahead = data.time - (time.perf_counter() - start)
        if ahead > 0:
            time.sleep(ahead)  # real-time speed
        viewer.sync()

    with viewer:
        loop.run(BuildHooks(on_frame=show, frame_dt=1.0 / 60.0))
    return 0


def cmd_sweep(args: argparse.Namespace) -> int:
    """Run what the grid lacks in its held folder's sweep.csv; exit 1 if a run crashed or timed
    out, as such a point measures nothing."""
    config = sweep_config_from_args(args)
    check_writable_dir(args.out)
    check_not_dataset(args.out)
    from ..physics.reach import prepare
    from ..sweep.run import report, run_sweep

    prepare(
        config.structure, SimConfig.for_robot(config.robot), config.arms
    )  # out of reach: refused
    runs = len(config.runs())
    with (
        removed_if_failed([args.out]),
        holding([(args.out, "out")]),
        Progress("sweep", runs, "build", quiet=args.quiet) as progress,
    ):
        rows, ran = run_sweep(  # the runs already in sweep.csv start the count
            config, args.out, on_row=lambda result: progress.advance(), on_skip=progress.start
        )
        table, plot = report(rows, config, args.out)
    print(table)
    ok = sum(r.success for r in rows)
    broken = [r for r in rows if r.broken]
    print(
        f"{ok}/{len(rows)} builds succeeded ({ran} run now, {runs - ran} already in the CSV) -> "
        f"{args.out / 'sweep.csv'}, {plot}"
    )
    if broken:
        print(
            f"sweep incomplete: {len(broken)} of {len(rows)} runs crashed or timed out, so "
            "their points measure nothing (see failure_reason in sweep.csv); the same command "
            "with --retry-failed (and a larger --timeout) runs them again",
            file=sys.stderr,
        )
    return 0 if len(rows) == runs and not broken else EXIT_FAILED


def cmd_scene(args: argparse.Namespace) -> int:
    """The compiled model a build of these options runs, with its bricks parked, to a file:
    of a size `build` takes (every pose checked by IK first, as `plan` and `build` do)."""
    config = config_from_args(args)
    spec = spec_from_args(args, config)
    if args.out.suffix.lower() not in (".mjb", ".xml"):
        raise ConfigError(f"out: {str(args.out)!r} must end in .mjb or .xml")
    check_writable_dir(args.out.parent)
    check_not_dataset(args.out.parent)
    check_file(args.out, "out", "scene", overwrite=args.overwrite)
    if args.out.suffix.lower() == ".xml":
        from ..output.scene_files import check_mesh_folder

        check_mesh_folder(args.out)
    from ..output.scene_files import write_scene
    from ..physics.reach import prepare

    plan = prepare(spec, config, args.arms)  # out of reach: refused, as `plan` refuses it
    # Held as every command holds what it writes: not into a folder a build is writing.
    with removed_if_failed([args.out.parent]), holding([(args.out.parent, "out")]):
        model, written = write_scene(config, len(plan.bricks) + config.spare_bricks, args.out)
    files = [str(args.out)] + [f"{p}/ ({len(list(p.iterdir()))} mesh files)" for p in written[1:]]
    print(
        f"{model.nbody} bodies, {model.ngeom} geoms, {model.nu} actuators, "
        f"{len(plan.bricks) + config.spare_bricks} bricks -> {', '.join(files)}"
    )
    return 0


def cmd_reach(args: argparse.Namespace) -> int:
    from ..core.structures import SIZE_KNOB, StructureSpec
    from ..learning.task.layout_reach import largest_in_every_layout
    from ..physics.reach import ReachChecker, held_fixed

    arm_sets: tuple[ArmChoice, ...] = ARM_CHOICES if args.arms == "all" else (args.arms,)
    checker = ReachChecker(SimConfig.for_robot(args.robot))
    arm_heads = [f"{a} arm{'s' if a == 'both' else ''}" for a in arm_sets]
    any_layout = args.any_layout and "both" in arm_sets
    layout_head = ["both arms, any layout"] if any_layout else []
    rows = [["structure", "grows", "other options", *arm_heads, *layout_head]]
    for name, knob in SIZE_KNOB.items():
        spec = StructureSpec(name)
        largest = {a: checker.largest(spec, a) for a in arm_sets}
        anywhere = (
            [str(largest_in_every_layout(checker, spec, "both", largest["both"] + 1))]
            if any_layout
            else []
        )
        rows.append([name, knob, held_fixed(spec), *map(str, largest.values()), *anywhere])
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    for r in rows:
        print("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip())
    print(REACH_CHECKS + (REACH_LAYOUTS if any_layout else ""))
    return 0


REACH_CHECKS = (
    "Checked by IK alone: every pose of the plan within the joints' ranges and clear of "
    "collisions, and each arm waiting at its clear pose outside the zone the arms take turns "
    "in (a wider structure reaches under a waiting arm). Not checked: joint speed, demanded torque with a brick held, and grip, which "
    "only a build measures; a size within reach can still fail on them."
)
REACH_LAYOUTS = (
    " 'any layout' (--any-layout): the learning environment's layout variation, checked at "
    "its region's corners (the structure shifted up to 5 cm and turned up to 15 degrees; the "
    "spawn spot 3 cm x 4 cm off, turned up to 20 degrees); a draw inside it still out of "
    "reach is drawn again."
)
