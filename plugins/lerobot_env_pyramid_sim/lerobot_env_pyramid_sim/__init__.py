"""pyramid_sim as a lerobot environment: `lerobot-eval --env.type=pyramid_sim
--env.task=pyramid-even --env.layers=1 --policy.path=CHECKPOINT` evaluates a policy trained
on a dataset `pyramid-sim record` wrote (the same features, the same names, the same rate).

lerobot imports this package by itself (its distribution's name starts with lerobot_env_);
the environment is pyramid_sim's `pyramid_sim/Lerobot-v0` (pyramid_sim.learning.lerobot_plugin.lerobot_env).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from lerobot.configs import FeatureType, PolicyFeature
from lerobot.envs.configs import EnvConfig
from lerobot.utils.constants import ACTION, OBS_ENV_STATE, OBS_IMAGES, OBS_STATE

import pyramid_sim
from pyramid_sim.choices import (
    DEFAULT_VARIATION,
    RECORD_CAMERAS,
    RECORD_FPS,
    RECORD_IMAGE_SIZE,
)
from pyramid_sim.robots import robot

SPARE_BRICKS = pyramid_sim.SimConfig().spare_bricks  # in the magazine beside the structure's


@EnvConfig.register_subclass("pyramid_sim")
@dataclass
class PyramidSimEnv(EnvConfig):
    """The task is a structure (pyramid, pyramid-even, wall, ...); `layers` its size, and the
    rest as `pyramid-sim record` takes them. `episode_length` is the step limit, at `fps`:
    by default `pyramid-sim evaluate`'s, 30 s a brick and 30 s more."""

    task: str | None = "pyramid-even"
    layers: int = 1
    robot: str = "panda"
    # A default recording's: a checkpoint trained on one evaluates with no more flags (a
    # state-only one: --env.cameras='[]').
    variation: str = DEFAULT_VARIATION
    fps: int = RECORD_FPS
    episode_length: int | None = None  # 2250 for two bricks at 25 fps
    cameras: tuple[str, ...] = RECORD_CAMERAS  # as `record --cameras`
    observation_height: int = RECORD_IMAGE_SIZE[0]
    observation_width: int = RECORD_IMAGE_SIZE[1]
    action_mode: str = "joint"  # as `record --action-mode`: joint, relative, waypoint, anchored
    brick_poses: bool = True  # as `record`: false for `--no-brick-poses`
    all_goals: bool = True  # and false for `--next-goals-only`
    features: dict[str, PolicyFeature] = field(default_factory=dict)
    features_map: dict[str, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        from pyramid_sim.learning.action_modes.registry import action_size
        from pyramid_sim.learning.lerobot_plugin.plugin_task import plugin_task, step_limit_given

        spec = plugin_task(self)  # ConfigError naming a field, as every caller's spec
        bricks = len(pyramid_sim.plan(spec.structure, layers=spec.layers, robot=spec.robot).bricks)
        if self.episode_length is None:  # MuJoCo's import: only when this env is asked for
            from pyramid_sim.learning.recording.episode import step_limit

            self.episode_length = step_limit(bricks, self.fps)
        self.episode_length = step_limit_given(self.episode_length)
        # each arm's joints and its gripper: 16 for the Panda pair and Baxter, 12 for the SO-101s
        motors = sum(len(arm.joints) + 1 for arm in robot(self.robot).arms.values())
        actions = action_size(self.action_mode, robot(self.robot))  # the mode's own count
        self.features = {
            ACTION: PolicyFeature(type=FeatureType.ACTION, shape=(actions,)),
            "agent_pos": PolicyFeature(type=FeatureType.STATE, shape=(motors,)),
            "environment_state": PolicyFeature(
                type=FeatureType.ENV,
                shape=(
                    len(
                        pyramid_sim.environment_names(bricks + SPARE_BRICKS, bricks, *spec.observed)
                    ),
                ),
            ),
        }
        self.features_map = {
            ACTION: ACTION,
            "agent_pos": OBS_STATE,
            "environment_state": OBS_ENV_STATE,
        }
        for camera in self.cameras:
            shape = (self.observation_height, self.observation_width, 3)
            self.features[f"pixels/{camera}"] = PolicyFeature(type=FeatureType.VISUAL, shape=shape)
            self.features_map[f"pixels/{camera}"] = f"{OBS_IMAGES}.{camera}"

    @property
    def package_name(self) -> str:
        return "pyramid_sim"

    @property
    def gym_id(self) -> str:
        return pyramid_sim.LEROBOT_ENV_ID

    @property
    def gym_kwargs(self) -> dict[str, Any]:
        from pyramid_sim.learning.lerobot_plugin.plugin_task import plugin_task

        # the environment takes the task spec whole (`make_lerobot_env`)
        return {"structure": plugin_task(self), "max_episode_steps": self.episode_length}
