"""What `record` and `evaluate` share: their episode flags, and what they run read from them."""

from __future__ import annotations

import argparse

from ..config import SimConfig
from ..core.structures import StructureSpec
from ..errors import ConfigError
from ..output.files import check_writable_dir
from ..params import EPISODES
from .args import SIZE_FLAGS, config_from_args, size_options, spec_from_args, whole
from .task_flags import EPISODE_FIELDS, add_task_flags


def add_episode_args(
    p: argparse.ArgumentParser, episodes: int, what: str, modes: tuple[str, ...]
) -> None:
    """--episodes, --variation, --fps and --action-mode (of `modes`), as record and evaluate
    share them."""
    from ..choices import ACTION_MODE_WORDS, RECORD_FPS, VARIATIONS

    p.add_argument(
        "--episodes",
        type=whole("episodes", EPISODES.whole_text),
        default=episodes,
        help=f"{what}, seeds --seed, --seed + 1, ... (default {episodes})",
    )
    words = {mode: ACTION_MODE_WORDS[mode] for mode in modes}
    add_task_flags(
        p, EPISODE_FIELDS, {"fps": RECORD_FPS}, {"variation": VARIATIONS, "action_mode": words}
    )


def episode_inputs(args: argparse.Namespace, verb: str) -> tuple[SimConfig, StructureSpec, dict]:
    """What `record` and `evaluate` run: the settings, the structure and its size options;
    ConfigError for an unwritable --out or a goals list (`verb`: what is not done to one)."""
    config = config_from_args(args)
    spec = spec_from_args(args, config)
    check_writable_dir(args.out)
    if spec.goals is not None:
        raise ConfigError(f"structure: list is not {verb} yet; accepted the generated structures")
    return config, spec, dict(spec.size)


def trained_defaults(p: argparse.ArgumentParser) -> None:
    """The flags a checkpoint's training fills where not given (`as_trained`), not given by
    default: the defaults the help names stand for them where no checkpoint says."""
    p.set_defaults(robot=None, structure=None, variation=None, fps=None, action_mode=None)


def as_trained(args: argparse.Namespace) -> argparse.Namespace:
    """The flags, those not given filled as the policy was trained (a checkpoint's, as
    `evaluate` and a DAgger round's `record --policy` read it) or with the defaults;
    ConfigError for one that contradicts a checkpoint's training. A checkpoint that observed
    no brick poses, or each arm's next goal alone, is fed the same."""
    from ..learning.lerobot_plugin.checkpoint_inputs import Task, checkpoint_task, checkpoint_views

    policy = args.policy or "expert"  # no policy: the defaults
    given = Task(
        args.robot, args.structure, size_options(args), args.variation, args.fps, args.action_mode
    )
    task = checkpoint_task(policy, given)
    sizes = {SIZE_FLAGS[k][0][2:].replace("-", "_"): v for k, v in task.size.items()}
    settled = {
        "robot": task.robot,
        "structure": task.structure,
        "variation": task.variation,
        "fps": task.fps,
        "action_mode": task.action_mode,
    }
    views = checkpoint_views(policy)
    hidden = {k: v for k, v in views.items() if v is False}  # what its observation left out
    return argparse.Namespace(**{**vars(args), **sizes, **settled, **hidden})
