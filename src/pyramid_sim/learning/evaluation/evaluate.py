"""`pyramid-sim evaluate`: a policy scored over held-out seeds, as learners score policies on
every peer. Episode i is `reset(seed=first_seed + i)`; evaluation seeds start at EVAL_SEED
(100000) by default, recordings at 0, so the two never overlap for recordings of fewer than
100000 episodes (`record` takes at most that many). `evaluation.json` holds the scores, the
inputs and versions, and one row an episode."""

from __future__ import annotations

import platform
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from gymnasium.wrappers import TimeLimit

from ...choices import EVAL_FIRST_SEED
from ...config import MotionConfig
from ...errors import ActionError, ConfigError, PolicyError
from ...options import plain_numbers
from ...output.files import atomic_path, write_json_atomic
from ...params import EPISODES, MAX_STEPS
from ...version import __version__
from ..env.env import BuildEnv
from ..recording.episode import step_limit
from ..task.layout import check_seed, control_steps
from ..task.variation import DEFAULT_LEVEL, check_level
from .policies import make_policy
from .scores import summary

EVAL_SEED = EVAL_FIRST_SEED  # recordings start at 0 (`record --seed`)
SPLIT = (
    "evaluation seeds first_seed..first_seed+episodes-1 (default from 100000); recordings "
    "use seeds from 0 (default), so they never overlap for recordings of fewer than 100000 "
    "episodes"
)


@dataclass(frozen=True)
class EvaluateConfig:
    """What an evaluation is: the policy, the task (structure, size and settings as `build`
    takes them, the variation and step rate), how many episodes from which seed, and how many
    of the first are filmed."""

    policy: str = "expert"
    structure: str = "pyramid-even"
    options: dict[str, Any] = field(default_factory=dict)  # sizes and settings
    variation: str = DEFAULT_LEVEL
    fps: int = 25
    episodes: int = 10
    first_seed: int = EVAL_SEED
    videos: int = 0  # the first episodes filmed from the overview camera
    max_steps: int | None = None  # an episode's step limit (default: `step_limit`)
    action_mode: str = "joint"  # the policy's: one of choices.ACTION_MODES

    def __post_init__(self) -> None:
        for name in ("fps", "episodes", "first_seed", "videos", "max_steps"):
            object.__setattr__(self, name, plain_numbers({name: getattr(self, name)})[name])
        EPISODES.check_whole(self.episodes)
        check_level(self.variation)
        control_steps(self.fps, MotionConfig().control_dt)
        check_seed(self.first_seed)
        check_seed(self.first_seed + self.episodes - 1)
        if self.max_steps is not None:
            MAX_STEPS.check_whole(self.max_steps)  # 1.5 steps reached Gymnasium's TimeLimit
        if not 0 <= self.videos <= self.episodes:
            raise ConfigError(
                f"video: {self.videos} episodes filmed; accepted 0 to the {self.episodes} run"
            )


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


def run_episode(env: Any, policy: Any, seed: int, film: Any = None) -> dict[str, Any]:
    """One episode of `policy` from `reset(seed=seed)` in `env` (a BuildEnv, wrapped or
    not): its row. An episode cut by a step limit fails for it. PolicyError if the policy's
    reset() or act() raises, or act() gives an action the environment does not take."""
    observation, _ = env.reset(seed=seed)
    _policy_call(policy.reset, "reset()")
    steps, start = 0, time.perf_counter()
    while True:
        action = _policy_call(policy.act, "act()", observation)
        try:
            observation, _, terminated, truncated, info = env.step(action)
        except ActionError as err:
            raise PolicyError(f"act() gave an {err}") from err
        steps += 1
        if film is not None:
            film(env.render())
        if terminated or truncated:
            break
    return {
        "seed": seed,
        "success": bool(info["is_success"]),
        "bricks_placed": int(info["bricks_placed"]),
        "failure": info["failure"] or (f"step limit: {steps} steps" if truncated else None),
        "truncated": bool(truncated),
        "steps": steps,
        "command_lag": float(info["command_lag"]),  # the motion generator's work, rad
        "sim_time_s": info["sim_time_s"],
        "wall_time_s": time.perf_counter() - start,
    }


def evaluate(
    config: EvaluateConfig,
    out: Path | None = None,
    on_episode: Callable[[dict[str, Any]], Any] | None = None,
) -> Evaluation:
    """Run the evaluation; with `out`, write `out/evaluation.json` (and the films,
    `out/episode_<seed>.mp4`)."""
    built = BuildEnv(
        config.structure,
        variation=config.variation,
        fps=config.fps,
        render_mode="rgb_array" if config.videos else None,
        action_mode=config.action_mode,
        **config.options,
    )
    limit = config.max_steps or step_limit(len(built.plan.bricks), config.fps)
    env = TimeLimit(built, max_episode_steps=limit)
    policy = make_policy(config.policy, env)
    rows = []
    try:
        for i in range(config.episodes):
            rows.append(_episode(env, policy, config, i, out))
            if on_episode is not None:
                on_episode(rows[-1])
    finally:
        env.close()
    scores = {
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
    path = None
    if out is not None:
        path = out / "evaluation.json"
        write_json_atomic(path, scores)
    return Evaluation(path, scores)


def _episode(env: Any, policy: Any, config: EvaluateConfig, i: int, out: Path | None) -> dict:
    """Episode `i`'s row, filmed if among the first `videos`; a PolicyError names the policy,
    the episode and its seed (the user's code: one line, and no evaluation.json)."""
    seed = config.first_seed + i
    try:
        if i < config.videos and out is not None:
            return _filmed(env, policy, seed, out / f"episode_{seed}.mp4", config.fps)
        return run_episode(env, policy, seed)
    except PolicyError as err:
        raise PolicyError(
            f"policy: {config.policy!r}, episode {i + 1} of {config.episodes} (seed {seed}): {err}"
        ) from err.__cause__


def _filmed(env: Any, policy: Any, seed: int, path: Path, fps: int) -> dict[str, Any]:
    """An episode filmed from the overview camera into `path`, a frame each step, streamed
    into a file that lands whole or not at all."""
    import imageio.v2 as imageio

    rows: list[dict[str, Any]] = []

    def film(tmp: Path) -> None:
        writer: Any = imageio.get_writer(str(tmp), format="FFMPEG", fps=fps, macro_block_size=1)
        with writer:
            rows.append(run_episode(env, policy, seed, writer.append_data))

    with atomic_path(path) as tmp:
        film(tmp)
    return rows[0]


def _policy_call(method: Callable[..., Any], what: str, *args: Any) -> Any:
    """`method(*args)` of a policy; PolicyError naming `what` raised what, if it raises."""
    try:
        return method(*args)
    except (Exception, SystemExit) as err:  # an exit too: the user's code, in one line
        raise PolicyError(f"{what} raised {type(err).__name__}: {err}") from err


def _plain(options: dict[str, Any]) -> dict[str, Any]:
    """The options as JSON takes them (a whole SimConfig as its fields)."""
    return {k: asdict(v) if hasattr(v, "__dataclass_fields__") else v for k, v in options.items()}
