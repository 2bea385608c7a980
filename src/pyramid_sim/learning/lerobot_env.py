"""The environment as lerobot's evaluation reads one (`lerobot-eval --env.type=pyramid_sim`,
through the `lerobot_env_pyramid_sim` plugin in plugins/): the observation under lerobot's
keys, `agent_pos` (observation.state), `environment_state` (observation.environment_state, the
bricks' poses flattened as `record` writes them) and `pixels` (each camera's image,
observation.images.<camera>), and the task's text. No lerobot import: it is a client."""

from __future__ import annotations

from typing import Any

import gymnasium
import numpy as np
from gymnasium import spaces

from ..choices import LEROBOT_ENV_ID
from .env import BuildEnv
from .episode import task_text

__all__ = ["LEROBOT_ENV_ID", "LerobotView", "lerobot_keys", "make_lerobot_env"]


class LerobotView(gymnasium.ObservationWrapper):
    """A BuildEnv whose observations carry lerobot's keys, with `task` and
    `task_description` (the text `record` gives each frame)."""

    def __init__(self, env: BuildEnv) -> None:
        super().__init__(env)
        inner = env.observation_space
        assert isinstance(inner, spaces.Dict)
        bricks = inner["bricks"].shape
        assert bricks is not None
        observed: dict[str, spaces.Space] = {
            "agent_pos": spaces.Box(-np.inf, np.inf, inner["state"].shape, dtype=np.float32),
            "environment_state": spaces.Box(
                -np.inf, np.inf, (bricks[0] * bricks[1],), dtype=np.float32
            ),
        }
        if "images" in inner.spaces:
            observed["pixels"] = inner["images"]
        self.observation_space = spaces.Dict(observed)
        self.task = self.task_description = task_text(env)

    def observation(self, observation: dict[str, Any]) -> dict[str, Any]:
        return lerobot_keys(observation)


def lerobot_keys(observation: dict[str, Any]) -> dict[str, Any]:
    """A BuildEnv observation under lerobot's keys."""
    mapped: dict[str, Any] = {
        "agent_pos": observation["state"].astype(np.float32),
        "environment_state": observation["bricks"].astype(np.float32).ravel(),
    }
    if "images" in observation:
        mapped["pixels"] = observation["images"]
    return mapped


def make_lerobot_env(structure: str = "pyramid-even", **options: Any) -> LerobotView:
    """`gymnasium.make(LEROBOT_ENV_ID, ...)`'s environment: a BuildEnv of `options` as lerobot
    sees it."""
    return LerobotView(BuildEnv(structure, **options))
