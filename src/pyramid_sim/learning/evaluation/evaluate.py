"""`pyramid-sim evaluate`: a policy scored over held-out seeds, as learners score policies on
every peer. Episode i is `reset(seed=first_seed + i)`; evaluation seeds start at EVAL_SEED
(100000) by default, recordings at 0, so the two never overlap for recordings of fewer than
100000 episodes (`record` takes at most that many). `evaluation.json` holds the scores, the
inputs and versions, and one row an episode. With `workers` (or Ray), the episodes are split
across worker processes (or Ray tasks), each with its own environment and policy: an episode
depends on its seed alone, so the scores are those of one worker, bit for bit."""

from __future__ import annotations

import platform
from collections.abc import Callable
from contextlib import nullcontext
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ...output.files import atomic_dir, write_json_atomic
from ...output.replay_tape import EPISODES_FOLDER, episode_name
from ...version import __version__
from .config import EVAL_SEED, SPLIT, EvaluateConfig
from .episodes import episode_row, make_env, run_episode
from .plot import PLOT_FILE, write_evaluation_plot
from .policies import make_policy
from .scores import summary
from .sharded import run_sharded

__all__ = ["EVAL_SEED", "EvaluateConfig", "Evaluation", "evaluate", "run_episode"]


@dataclass(frozen=True)
class Evaluation:
    """A finished evaluation: its scores (as evaluation.json has them) and where it is."""

    path: Path | None
    scores: dict[str, Any]

    @property
    def success_rate(self) -> float:
        return float(self.scores["success_rate"])

    def line(self) -> str:
        """The summary line the command prints."""
        s = self.scores
        low, high = (100 * v for v in s["success_rate_95"])
        where = f" -> {self.path}" if self.path is not None else ""
        return (
            f"evaluated: {s['policy']} {s['successes']}/{s['episodes']} successes "
            f"({100 * s['success_rate']:.1f} %, 95 % interval {low:.1f}-{high:.1f}), "
            f"{s['bricks_placed_mean']:.2f} of {s['bricks']} bricks placed on average{where}"
        )


def versions() -> dict[str, str]:
    """The versions that produced an evaluation."""
    import gymnasium
    import mink
    import mujoco

    return {
        "pyramid_sim": __version__,
        "mujoco": mujoco.__version__,
        "mink": getattr(mink, "__version__", "unknown"),
        "gymnasium": gymnasium.__version__,
        "numpy": np.__version__,
        "python": platform.python_version(),
    }


def evaluate(
    config: EvaluateConfig,
    out: Path | None = None,
    on_episode: Callable[[dict[str, Any]], Any] | None = None,
) -> Evaluation:
    """Run the evaluation; with `out`, write `out/evaluation.json`, its plot
    `out/evaluation.png`, each episode's poses `out/replay/` (and the films,
    `out/episode_<seed>.mp4`)."""
    env = make_env(config)
    # the episodes' poses land with evaluation.json, replacing an earlier evaluation's whole
    staging = nullcontext(None) if out is None else atomic_dir(out / EPISODES_FOLDER)
    with staging as replays:
        try:
            rows = _rows(env, config, out, on_episode, replays)
        finally:
            env.close()
        scores = _scores(config, env, rows)
        if out is not None:
            write_json_atomic(out / "evaluation.json", scores)
            write_evaluation_plot(scores, out / PLOT_FILE)
    return Evaluation(None if out is None else out / "evaluation.json", scores)


def _rows(
    env: Any,
    config: EvaluateConfig,
    out: Path | None,
    on_episode: Callable[[dict[str, Any]], Any] | None,
    replays: Path | None,
) -> list[dict[str, Any]]:
    """The episodes' rows, run here or by workers; their poses taped into `replays`."""
    policy = make_policy(config.policy, env)  # a bad policy refused before any worker
    if config.workers > 1 or config.backend == "ray":
        return run_sharded(config, out, on_episode, replays)
    rows = []
    for i in range(config.episodes):
        taped = None if replays is None else replays / episode_name(i)
        rows.append(episode_row(env, policy, config, i, out, replay=taped))
        if on_episode is not None:
            on_episode(rows[-1])
    return rows


def _scores(config: EvaluateConfig, env: Any, rows: list[dict[str, Any]]) -> dict[str, Any]:
    """evaluation.json's document."""
    built, limit = env.unwrapped, env._max_episode_steps
    return {
        "policy": config.policy,
        **summary(rows, len(built.plan.bricks)),
        "protocol": {
            "first_seed": config.first_seed,
            "seeds": [config.first_seed, config.first_seed + config.episodes - 1],
            "split": SPLIT,
            "success": "every target holds a brick at rest within the build's tolerances",
        },
        "task": {
            "structure": built.plan.spec.name,
            "size": dict(built.plan.spec.size),
            "robot": built.config.robot,
            "variation": config.variation,
            "fps": config.fps,
            "limit_commands": built.limit_commands,
            "action_mode": config.action_mode,
            "max_steps": limit,
        },
        "inputs": {**asdict(config), "options": _plain(config.options)},
        "settings": asdict(built.config),
        "versions": versions(),
        "rows": rows,
    }


def _plain(options: dict[str, Any]) -> dict[str, Any]:
    """The options as JSON takes them (a whole SimConfig as its fields)."""
    return {k: asdict(v) if hasattr(v, "__dataclass_fields__") else v for k, v in options.items()}
