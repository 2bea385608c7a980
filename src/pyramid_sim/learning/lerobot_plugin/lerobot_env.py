"""The environment as lerobot's evaluation reads one (`lerobot-eval --env.type=pyramid_sim`,
through the `lerobot_env_pyramid_sim` plugin in plugins/): the observation under lerobot's
keys, `agent_pos` (observation.state), `environment_state` (observation.environment_state, the
bricks' poses and the targets', flattened as `record` writes them) and `pixels` (each camera's image,
observation.images.<camera>), and the task's text; `render()` films the overview camera. No
lerobot import: it is a client."""

from __future__ import annotations

from typing import Any

import gymnasium
import numpy as np
from gymnasium import spaces

from ...choices import LEROBOT_ENV_ID
from ..env.env import BuildEnv
from ..recording.episode import task_text
from ..task.lerobot_units import LerobotUnits
from ..task.observation_names import environment_names
from ..task.spaces import environment_state
from ..task.spec import TaskSpec

__all__ = [
    "LEROBOT_ENV_ID",
    "NEW_ROLLOUT_OPTION",
    "LerobotView",
    "lerobot_keys",
    "make_lerobot_env",
]

# lerobot-eval's mark on every reset that starts a rollout (lerobot.envs.utils): a signal to
# its own wrappers, not an option of the episode, which is drawn from its seed alone.
NEW_ROLLOUT_OPTION = "lerobot_new_rollout"


class LerobotView(gymnasium.Wrapper):
    """A BuildEnv whose observations carry lerobot's keys, with `task` and
    `task_description` (the text `record` gives each frame), its state and joint commands in
    lerobot's units for the robot, as `record` writes them (learning/task/lerobot_units.py)."""

    def __init__(self, env: BuildEnv) -> None:
        super().__init__(env)
        self.units, self.action_units = env.lerobot_units, env.action_units
        inner_action = env.action_space
        assert isinstance(inner_action, spaces.Box)
        ends = self.action_units.to_lerobot(np.stack([inner_action.low, inner_action.high]))
        self.action_space = spaces.Box(ends.min(0), ends.max(0), dtype=np.float32)
        inner = env.observation_space
        assert isinstance(inner, spaces.Dict)
        self.environment_names = environment_names(
            env.layout.bricks, len(env.plan.bricks), *env.observed
        )
        observed: dict[str, spaces.Space] = {
            "agent_pos": spaces.Box(-np.inf, np.inf, inner["state"].shape, dtype=np.float32),
            "environment_state": spaces.Box(
                -np.inf, np.inf, (len(self.environment_names),), dtype=np.float32
            ),
        }
        if "images" in inner.spaces:
            observed["pixels"] = inner["images"]
        self.observation_space = spaces.Dict(observed)
        self.task = self.task_description = task_text(env)

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, Any], dict[str, Any]]:
        """The episode of `seed`; lerobot-eval's rollout mark is taken off `options`, and
        any other option is refused by the environment as ever."""
        ours = options
        if isinstance(options, dict) and NEW_ROLLOUT_OPTION in options:
            ours = {k: v for k, v in options.items() if k != NEW_ROLLOUT_OPTION}
        observation, info = self.env.reset(seed=seed, options=ours)
        return lerobot_keys(observation, self.units), info

    def step(self, action: Any) -> tuple[dict[str, Any], float, bool, bool, dict[str, Any]]:
        ours = self.action_units.from_lerobot(action)
        observation, reward, terminated, truncated, info = self.env.step(
            np.asarray(ours, dtype=np.float32)
        )
        return lerobot_keys(observation, self.units), float(reward), terminated, truncated, info


def lerobot_keys(observation: dict[str, Any], units: LerobotUnits) -> dict[str, Any]:
    """A BuildEnv observation under lerobot's keys, its state in lerobot's units."""
    mapped: dict[str, Any] = {
        "agent_pos": units.to_lerobot(observation["state"]),
        "environment_state": environment_state(observation),
    }
    if "images" in observation:
        mapped["pixels"] = observation["images"]
    return mapped


def make_lerobot_env(structure: str | TaskSpec = "pyramid-even", **options: Any) -> LerobotView:
    """`gymnasium.make(LEROBOT_ENV_ID, ...)`'s environment: a BuildEnv of `options` as lerobot
    sees it. It renders the overview camera at a film's size (640 x 480, as `evaluate
    --video`) whatever the policy observes: lerobot-eval films every evaluation, and writes
    a film of frames it was not given as a traceback and a missing file. The renderer is made
    at the first frame asked for."""
    if isinstance(structure, TaskSpec):
        return LerobotView(BuildEnv(TaskSpec.of(structure, **options)))
    return LerobotView(BuildEnv(structure, **{"render_mode": "rgb_array", **options}))
