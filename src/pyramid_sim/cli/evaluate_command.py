"""`pyramid-sim evaluate`: a policy scored over held-out seeds, its flags and its run."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..choices import ACTION_MODES, EVAL_FIRST_SEED
from ..params import MAX_STEPS, WORKERS
from .args import (
    add_backend_args,
    add_out_args,
    add_physics_args,
    add_schedule_arg,
    add_structure_args,
    whole,
)
from .episode_args import add_episode_args, as_trained, episode_inputs, trained_defaults
from .paths import policies_from_here
from .progress import Progress
from .targets import add_overwrite_arg, check_evaluate_targets


def add_evaluate_args(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--policy",
        default="expert",
        metavar="POLICY",
        help="expert, zero (hold still), random, module:factory (called with the environment; "
        "the current folder is on the import path, as with python -m), or a lerobot "
        "checkpoint folder (where lerobot is installed), evaluated on the robot, structure, "
        "size, variation, fps and action mode it was trained on unless given (default expert)",
    )
    add_structure_args(p)
    add_physics_args(
        p,
        seed_default=EVAL_FIRST_SEED,
        seed_help=f"the first episode's; episode i is seed + i (default {EVAL_FIRST_SEED}: "
        "recordings start at 0)",
    )
    add_schedule_arg(p)
    add_episode_args(p, 10, "episodes scored", ACTION_MODES)
    p.add_argument(
        "--max-steps",
        type=whole("max steps", MAX_STEPS.whole_text),
        default=None,
        help="an episode's step limit (default 30 s a brick and 30 s more)",
    )
    p.add_argument(
        "--video",
        type=whole("video", "0 to --episodes"),
        default=0,
        metavar="N",
        help="film the first N episodes from the overview camera, DIR/episode_<seed>.mp4",
    )
    p.add_argument(
        "--workers",
        type=whole("workers", WORKERS.whole_text),
        default=1,
        help="episodes run at once, each in a process or a Ray task with its own environment "
        "and policy; the scores are one worker's (default 1)",
    )
    add_backend_args(p, "episodes")
    add_out_args(p, Path("runs/evaluation"))
    add_overwrite_arg(p, "an evaluation.json or film")
    trained_defaults(p)


def cmd_evaluate(args: argparse.Namespace) -> int:
    """Score the policy; writes DIR/evaluation.json and prints its summary line."""
    import pyramid_sim

    args = as_trained(args)
    config, spec, sizes = episode_inputs(args, "evaluated")
    policies_from_here()
    check_evaluate_targets(args, config, spec.size)
    # the library holds --out, and removes it if it made it and fails
    with Progress("episodes", args.episodes, "episode", quiet=args.quiet) as progress:
        progress.start()
        evaluation = pyramid_sim.evaluate(
            args.policy,
            spec.name,
            out=args.out,
            arms=args.arms,
            variation=args.variation,
            fps=args.fps,
            action_mode=args.action_mode,
            episodes=args.episodes,
            seed=config.seed,
            video=args.video,
            max_steps=args.max_steps,
            workers=args.workers,
            backend=args.backend,
            ray_address=args.ray_address,
            on_episode=lambda row: progress.advance(),
            config=config,
            **sizes,
        )
    print(evaluation.line())
    return 0
