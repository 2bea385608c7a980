"""The task spec of lerobot's plugin config (`lerobot-eval --env.type=pyramid_sim`): its
fields, named as lerobot names an environment's (`task`, `observation_height`, ...), made into
one `TaskSpec` and checked as every other caller's spec is, and the episode's step limit.
MuJoCo-free: lerobot makes the config before it asks for the environment."""

from __future__ import annotations

from dataclasses import fields
from typing import Any

from ...errors import ConfigError
from ...params import MAX_STEPS
from ..task.spec import TaskSpec

# A spec's fields the plugin names its own way, or does not offer (the rest it shares)
NOT_SHARED = ("structure", "cameras", "image_size", "render_mode", "settings", "config")


def plugin_task(config: Any) -> TaskSpec:
    """The spec the plugin's `config` asks for (`task` is the structure, the images
    `observation_height` x `observation_width`), filmed for lerobot-eval (`rgb_array`);
    ConfigError naming the field otherwise."""
    names = (f.name for f in fields(TaskSpec) if f.name not in NOT_SHARED)
    shared = {name: getattr(config, name) for name in names if hasattr(config, name)}
    if not isinstance(config.task, str):
        raise ConfigError(f"task: {config.task!r} is not a structure's name; accepted a name")
    return TaskSpec(
        config.task,
        **shared,
        cameras=tuple(config.cameras),
        image_size=(config.observation_height, config.observation_width),
        render_mode="rgb_array",
    )


def step_limit_given(episode_length: Any) -> int:
    """`episode_length` as the plugin's step limit; ConfigError naming its range for one that
    is not a whole number of steps within MAX_STEPS (0 or -5 would end every episode at once)."""
    whole = isinstance(episode_length, int) and not isinstance(episode_length, bool)
    if not (whole and MAX_STEPS.low <= episode_length <= MAX_STEPS.high):
        raise ConfigError(
            f"episode length: {episode_length!r}; accepted {MAX_STEPS.whole_text} steps, or "
            "None for 30 s a brick and 30 s more"
        )
    return int(episode_length)
