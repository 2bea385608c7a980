"""An episode of the scripted expert filmed into a LeRobot episode's files: the features a
recording's frames carry, the roll-out, and the same film run here or in a worker (the
stager, learning/recording/staging.py, is handed `film_staged` or a `FilmAway`)."""

from __future__ import annotations

import shutil
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any, cast

from ...errors import ConfigError
from ...output.replay_tape import EPISODES_FOLDER, EpisodeTape, Taping, episode_name
from ..dataset import lerobot_format as fmt
from ..env.env import BuildEnv
from ..task.observation_names import environment_names
from .dagger import Mixer, bounded, taken_over
from .episode import Frame, expert_episode
from .record_config import RecordConfig
from .staging import REFUSED, staging_folder

# What makes a DAgger round's learner for an environment from its `--policy` text (the
# evaluation's policy maker, handed down by whoever records: recording sits below it)
PolicyMaker = Callable[[str, Any], Any]


def make_env(config: RecordConfig) -> BuildEnv:
    """The environment a recording's episodes run in, stepping at its frame rate."""
    return BuildEnv(config.task)


def features(env: BuildEnv, config: RecordConfig) -> dict[str, fmt.Feature]:
    """The dataset's per-frame features, from the environment's layout."""
    names = env.lerobot_units.names  # lerobot's, for a robot it records (the SO-101 pair)
    actions = env.action_units.names  # a hand's pose for the waypoint mode
    height, width = config.image_size
    environment = environment_names(env.layout.bricks, len(env.plan.bricks), *config.observed)
    found = {
        "observation.state": fmt.Feature("float32", (len(names),), names),
        "observation.environment_state": fmt.Feature("float32", (len(environment),), environment),
        "action": fmt.Feature("float32", (len(actions),), actions),
    }
    for camera in config.cameras:
        found[f"observation.images.{camera}"] = fmt.Feature("video", (height, width, 3))
    found["next.reward"] = fmt.Feature("float32", (1,))
    found["next.done"] = fmt.Feature("bool", (1,))
    found["next.success"] = fmt.Feature("bool", (1,))
    for arm in ("left", "right"):
        found[f"primitive.{arm}"] = fmt.Feature("int64", (1,))  # an index into PRIMITIVES
        found[f"brick.{arm}"] = fmt.Feature("int64", (1,))  # build order, -1 for none
    return found


def _frame_values(frame: Frame, cameras: tuple[str, ...], env: BuildEnv) -> dict[str, Any]:
    values: dict[str, Any] = {
        "observation.state": env.lerobot_units.to_lerobot(frame.state),
        "observation.environment_state": frame.environment,
        "action": env.action_units.to_lerobot(frame.action),
        "next.reward": frame.reward,
        "next.done": frame.done,
        "next.success": frame.success,
        "primitive.left": frame.primitive[0],
        "primitive.right": frame.primitive[1],
        "brick.left": frame.brick[0],
        "brick.right": frame.brick[1],
    }
    for camera in cameras:
        values[f"observation.images.{camera}"] = frame.images[camera]
    return values


def film_staged(
    env: BuildEnv,
    config: RecordConfig,
    episode: int,
    out: Path,
    on_frame: Callable[[int, int], Any] | None = None,
    learner: Any = None,
) -> dict[str, Any]:
    """Film one episode into its staging folder under `out` (with a `learner`, DAgger's
    round: dagger.py): how it ended, its draw and its row (frames indexed from 0)."""
    root = staging_folder(out, episode)
    shutil.rmtree(root, ignore_errors=True)
    files = fmt.EpisodeFiles(root, episode, config.fps, features(env, config))
    tape = EpisodeTape(root / EPISODES_FOLDER / episode_name(episode), config.first_seed + episode)
    end, row = film_episode(env, files, config, on_frame, learner, tape)
    files.commit()  # into the staging folder: the dataset sees nothing yet
    return {"episode": episode, "end": end, "randomization": env.drawn, "row": row}


_WORKER_ENV: dict[str, Any] = {}  # this process's environment and the recording it is for


@dataclass(frozen=True)
class FilmAway:
    """An episode filmed in a worker process or a Ray task, its environment (and a DAgger
    round's learner, made by `policies`) made once per process (picklable: the stager hands
    it to the job runner)."""

    config: RecordConfig
    policies: PolicyMaker | None = None

    def __call__(self, episode: int, out: Path) -> dict[str, Any]:
        if _WORKER_ENV.get("config") != self.config:  # a Ray worker may serve two recordings
            if "env" in _WORKER_ENV:
                _WORKER_ENV.pop("env").close()
            env = _WORKER_ENV["env"] = make_env(self.config)
            _WORKER_ENV["config"] = self.config
            _WORKER_ENV["learner"] = learner_for(env, self.config, self.policies)
        env, learner = _WORKER_ENV["env"], _WORKER_ENV["learner"]
        try:
            return film_staged(env, self.config, episode, out, learner=learner)
        except ConfigError as err:  # a learner's failure: handed back, said as one process does
            return {REFUSED: err}


def learner_for(env: BuildEnv, config: RecordConfig, policies: PolicyMaker | None) -> Any:
    """A DAgger round's learner for `env` (None for the expert's own recording)."""
    if config.policy is None:
        return None
    if policies is None:
        raise ValueError("a recording driven by a policy needs the policy maker")
    return policies(config.policy, env)


def film_episode(
    env: BuildEnv,
    files: fmt.EpisodeFiles,
    config: RecordConfig,
    on_frame: Callable[[int, int], Any] | None,
    learner: Any = None,
    tape: EpisodeTape | None = None,
) -> tuple[Any, dict[str, Any]]:
    """Roll the expert out into `files` (a `learner` driving DAgger's share of it; the
    bodies' poses into `tape`); how it ended and its metadata row. A run stopped midway
    leaves none of the episode's files."""
    frames = 0

    def keep(frame: Frame) -> None:
        nonlocal frames
        files.add(_frame_values(frame, config.cameras, env))
        frames += 1
        if on_frame is not None:
            on_frame(files.episode, frames)

    try:
        seed = config.first_seed + files.episode
        scale = env.config.robot_description.length_scale
        bound = (
            partial(bounded, env.mode, scale=scale)
            if config.takeover is None
            else partial(taken_over, env.mode, threshold=config.takeover, scale=scale)
        )
        mixer = None if learner is None else Mixer(learner, config.fps, seed, config.beta, bound)
        rolled = env if tape is None else cast(BuildEnv, Taping(env, tape))
        end = expert_episode(rolled, seed, config.cameras, keep, config.noise, mixer)
        if tape is not None:
            ended = "success" if end.success else f"failure ({end.failure})"
            tape.save(f"{env.plan.spec.name}, episode {files.episode} (seed {seed}): {ended}")
        return end, files.close()
    except BaseException:
        files.abort()
        raise
