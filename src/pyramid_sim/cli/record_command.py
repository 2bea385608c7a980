"""`pyramid-sim record`: the expert's builds as a LeRobot dataset, its flags and its run."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..choices import EVAL_FIRST_SEED, RECORD_ACTION_MODES, RECORD_IMAGE_SIZE, RECORD_LINGER
from ..errors import ConfigError
from ..params import BETA, NOISE, TAKEOVER, WORKERS
from .args import (
    add_backend_args,
    add_out_args,
    add_physics_args,
    add_schedule_arg,
    add_structure_args,
    bounded,
    whole,
)
from .episode_args import add_episode_args, as_trained, episode_inputs, trained_defaults
from .paths import policies_from_here
from .progress import Progress
from .task_flags import RECORD_FIELDS, add_task_flags, switches, task_values

CAMERAS_DEFAULT = "overview,left_wrist,right_wrist"


def add_record_args(p: argparse.ArgumentParser) -> None:
    add_structure_args(p)
    add_physics_args(
        p,
        seed_help=f"the first episode's; episode i is seed + i (default 0: evaluations start at "
        f"{EVAL_FIRST_SEED})",
    )
    add_schedule_arg(p)
    add_episode_args(p, 1, "whole builds", RECORD_ACTION_MODES)
    defaults = {"cameras": CAMERAS_DEFAULT, "image_size": None, "randomize": ""}
    add_task_flags(p, RECORD_FIELDS[:3], defaults)
    _add_run_args(p)
    trained_defaults(p)  # a DAgger round's checkpoint: its training's task


def _add_run_args(p: argparse.ArgumentParser) -> None:
    """How the episodes are run: workers, DART's noise, the linger after a success, the
    repair of damaged episodes, the backend and the folder."""
    p.add_argument(
        "--workers",
        type=whole("workers", WORKERS.whole_text),
        default=1,
        help="episodes filmed at once, each in a process or a Ray task (default 1)",
    )
    p.add_argument(
        "--noise",
        type=bounded(NOISE),
        default=0.0,
        metavar="SCALE",
        help="DART: each joint's executed target (rad), or in the waypoint and anchored modes "
        "each hand's x, y and z (m), off the expert's by an offset drawn every second from "
        f"N(0, SCALE), the expert's correction kept as the label; {NOISE.text} (default 0)",
    )
    add_task_flags(p, ("linger",), {"linger": RECORD_LINGER})
    p.add_argument(
        "--repair",
        action="store_true",
        help="record again the episodes of DIR whose files are damaged (cut short, or not "
        "the frames their records claim) (default: refuse to resume over them)",
    )
    _add_dagger_args(p)
    add_task_flags(p, switches(), {})
    add_backend_args(p, "episodes")
    add_out_args(p, Path("runs/dataset"))


def _add_dagger_args(p: argparse.ArgumentParser) -> None:
    """--policy, --beta and --takeover: a DAgger round (learning/recording/dagger.py)."""
    p.add_argument(
        "--policy",
        default=None,
        metavar="POLICY",
        help="DAgger: a policy (a lerobot checkpoint folder, or as evaluate takes one) drives "
        "the arms in the 2 s spans the expert does not, and the expert labels every frame; "
        "a round's episodes may be added to the dataset its policy was trained on "
        "(default none: the expert drives)",
    )
    p.add_argument(
        "--beta",
        type=bounded(BETA),
        default=None,
        metavar="SHARE",
        help=f"with --policy, DAgger's beta: the share of spans the expert drives; {BETA.text} "
        "(default 0.5; refused without --policy)",
    )
    p.add_argument(
        "--takeover",
        type=bounded(TAKEOVER),
        default=None,
        metavar="M",
        help="with --policy, HG-DAgger's gate: the learner's own actions kept while its hands "
        f"are within M metres of the expert's way, the expert taking the rest of the span past "
        f"it; {TAKEOVER.text} (default none: each hand pulled back to within 5 mm)",
    )


def cmd_record(args: argparse.Namespace) -> int:
    """Record what the dataset lacks; exit 1 if an episode's build failed (it is kept)."""
    import pyramid_sim

    args = as_trained(args)  # --policy CKPT: the task its training saw, where not given
    config, spec, sizes = episode_inputs(args, "recorded")
    flags = task_values(args)  # the spec's fields, as their flags gave them
    flags["cameras"] = _cameras(args.cameras, args.image_size)
    flags["image_size"] = args.image_size or RECORD_IMAGE_SIZE
    flags["randomize"] = _names(args.randomize)
    task = pyramid_sim.TaskSpec(spec.name, arms=args.arms, config=config, **sizes, **flags)
    if args.policy is not None:  # a DAgger round's learner, found as evaluate finds one
        policies_from_here()
    # the library holds --out, and removes it if it made it and fails
    with Progress(
        "episodes", args.episodes, "episode", quiet=args.quiet, count_unit="frame"
    ) as progress:
        on_frame, on_episode = progress.recording_hooks()
        recorded = pyramid_sim.record(
            task,
            out=args.out,
            episodes=args.episodes,
            seed=config.seed,
            on_frame=on_frame,
            on_episode=on_episode,
            workers=args.workers,
            backend=args.backend,
            ray_address=args.ray_address,
            noise=args.noise,
            **_driver(args.policy, args.beta, args.takeover),
            repair=args.repair,
        )
        progress.advance_to(args.episodes)
    failed = (
        f", {len(recorded.failed)} failed (kept: {list(recorded.failed)})"
        if recorded.failed
        else ""
    )
    print(
        f"recorded: {recorded.episodes} episodes ({recorded.added} now), {recorded.frames} "
        f"frames{failed} -> {args.out}"
    )
    return 1 if recorded.failed else 0


def _driver(policy: str | None, beta: float | None, takeover: float | None) -> dict[str, object]:
    """A DAgger round's `policy`, `beta` and `takeover`, those given (either of the last two
    without a policy is refused by the recording)."""
    given = {"policy": policy, "beta": beta, "takeover": takeover}
    return {k: v for k, v in given.items() if v is not None}


def _cameras(text: str, size: tuple[int, int] | None) -> tuple[str, ...]:
    """The cameras --cameras names (none: no video); ConfigError for a list that names none,
    and for an --image-size given with none (it would film nothing)."""
    if text.strip() == "none":
        if size is not None:
            raise ConfigError(
                f"image size: {size[0]}x{size[1]} with --cameras none films nothing; accepted "
                "--image-size with a camera"
            )
        return ()
    names = _names(text)
    if not names:
        raise ConfigError(
            f"cameras: {text!r} names none; accepted none (no video), or some of overview, "
            "front, top, left_wrist, right_wrist"
        )
    return names


def _names(text: str) -> tuple[str, ...]:
    """A comma-separated list's names."""
    return tuple(name.strip() for name in text.split(",") if name.strip())
