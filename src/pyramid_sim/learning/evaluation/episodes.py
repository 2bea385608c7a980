"""One episode of a policy in an evaluation's environment, and its row: run here, or in a
worker (sharded.py), filmed or not."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from gymnasium.wrappers import TimeLimit

from ...errors import ActionError, PolicyError
from ...output.files import atomic_path
from ...output.replay_tape import EpisodeTape
from ..env.env import BuildEnv
from ..recording.episode import step_limit
from ..recording.policy_calls import policy_call
from .config import EvaluateConfig
from .failure_site import failure_site


def make_env(config: EvaluateConfig) -> Any:
    """The environment an evaluation's episodes run in, cut at its step limit."""
    built = BuildEnv(
        config.structure,
        variation=config.variation,
        fps=config.fps,
        render_mode="rgb_array" if config.videos else None,
        action_mode=config.action_mode,
        **config.options,
    )
    limit = config.max_steps or step_limit(len(built.plan.bricks), config.fps)
    return TimeLimit(built, max_episode_steps=limit)


def run_episode(
    env: Any, policy: Any, seed: int, film: Any = None, tape: EpisodeTape | None = None
) -> dict[str, Any]:
    """One episode of `policy` from `reset(seed=seed)` in `env` (a BuildEnv, wrapped or
    not): its row (and, with `tape`, its poses for a replay). An episode cut by a step limit
    fails for it. PolicyError if the policy's reset() or act() raises, or act() gives an
    action the environment does not take."""
    observation, _ = env.reset(seed=seed)
    if tape is not None:
        tape.start(env)
    policy_call(policy.reset, "reset()")
    steps, start = 0, time.perf_counter()
    while True:
        action = policy_call(policy.act, "act()", observation)
        try:
            observation, _, terminated, truncated, info = env.step(action)
        except ActionError as err:
            raise PolicyError(f"act() gave an {err}") from err
        steps += 1
        if film is not None:
            film(env.render())
        if tape is not None:
            tape.step(env)
        if terminated or truncated:
            break
    row = {
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
    # read now, before the next reset: the brick and the primitive the failure happened on
    row["failed_at"] = None if row["success"] else failure_site(env)
    if tape is not None:
        tape.save(episode_title(env, row))
    return row


def episode_title(env: Any, row: dict[str, Any]) -> str:
    """A replay's heading: the structure, the seed, and how the episode ended."""
    ended = "success" if row["success"] else f"failure ({row['failure']})"
    placed = f"{row['bricks_placed']}/{len(env.unwrapped.plan.bricks)} bricks placed"
    return f"{env.unwrapped.plan.spec.name}, seed {row['seed']}: {ended}, {placed}"


def episode_row(
    env: Any,
    policy: Any,
    config: EvaluateConfig,
    i: int,
    out: Path | None,
    film: Path | None = None,
    replay: Path | None = None,
) -> dict:
    """Episode `i`'s row, filmed if among the first `videos` (into `out`, or the file
    `film`), its poses taped for a replay into the file `replay`, if given; a PolicyError
    names the policy, the episode and its seed (the user's code: one line, and no
    evaluation.json)."""
    seed = config.first_seed + i
    if film is None and out is not None and i < config.videos:
        film = out / f"episode_{seed}.mp4"
    tape = None if replay is None else EpisodeTape(replay, seed)
    try:
        if film is not None:
            return _filmed(env, policy, seed, film, config.fps, tape)
        return run_episode(env, policy, seed, tape=tape)
    except PolicyError as err:
        raise PolicyError(
            f"policy: {config.policy!r}, episode {i + 1} of {config.episodes} (seed {seed}): {err}"
        ) from err.__cause__


def _filmed(
    env: Any, policy: Any, seed: int, path: Path, fps: int, tape: EpisodeTape | None
) -> dict[str, Any]:
    """An episode filmed from the overview camera into `path`, a frame each step, streamed
    into a file that lands whole or not at all."""
    import imageio.v2 as imageio

    rows: list[dict[str, Any]] = []

    def film(tmp: Path) -> None:
        writer: Any = imageio.get_writer(str(tmp), format="FFMPEG", fps=fps, macro_block_size=1)
        with writer:
            rows.append(run_episode(env, policy, seed, writer.append_data, tape))

    with atomic_path(path) as tmp:
        film(tmp)
    return rows[0]
