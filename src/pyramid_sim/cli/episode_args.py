"""What `record` and `evaluate` share: their episode flags, and what they run read from them."""

from __future__ import annotations

import argparse

from ..choices import ACTION_MODE_WORDS, FPS_CHOICES
from ..config import SimConfig
from ..core.structures import StructureSpec
from ..errors import ConfigError
from ..output.files import check_writable_dir
from ..params import EPISODES
from .args import config_from_args, spec_from_args, whole


def add_episode_args(
    p: argparse.ArgumentParser, episodes: int, what: str, modes: tuple[str, ...]
) -> None:
    """--episodes, --variation, --fps and --action-mode (of `modes`), as record and evaluate
    share them."""
    from ..choices import DEFAULT_VARIATION, VARIATIONS

    p.add_argument(
        "--episodes",
        type=whole("episodes", EPISODES.whole_text),
        default=episodes,
        help=f"{what}, seeds --seed, --seed + 1, ... (default {episodes})",
    )
    p.add_argument(
        "--variation",
        default=DEFAULT_VARIATION,
        choices=VARIATIONS,
        help="how episodes differ: fixed (DE NIRO's layout), layout (the feed spot, the "
        "structure's place and turn drawn per episode) or full (the layout and every "
        f"randomization) (default {DEFAULT_VARIATION})",
    )
    p.add_argument(
        "--fps",
        type=whole("fps", ", ".join(map(str, FPS_CHOICES))),
        default=25,
        help="the environment's step rate, a dataset's frames a second (of the 100 Hz "
        "control): 10, 20, 25, 50 or 100 (default 25)",
    )
    p.add_argument(
        "--action-mode",
        default="joint",
        choices=modes,
        help=f"the action: {', '.join(ACTION_MODE_WORDS[m] for m in modes)} (default joint)",
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
