"""One expert demonstration: the scripted builder rolled out in the environment from a seed,
its frames kept at the dataset's rate and handed to a sink as they come (a film of a long
build never sits in memory)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ...errors import ActionError, PolicyError
from ..env.env import BuildEnv
from ..task.spaces import environment_state
from .dagger import Mixer
from .frame import Frame
from .lead_labels import LeadLabels

# What an arm is doing at a frame, by its index here (-1 never occurs: idle is 0).
PRIMITIVES = (
    "idle",
    "hover",
    "approach",
    "servo",
    "grip",
    "release",
    "retract",
    "clear",
    "standby",
)


TASK = "Build the {structure} ({size}) with two {robot} arms, one brick at a time."


def task_text(env: BuildEnv) -> str:
    """The task a recording's frames and an evaluation's policy are given, in words."""
    spec, robot = env.plan.spec, env.config.robot_description.name
    return TASK.format(structure=spec.name, size=spec.size_text(), robot=robot)


@dataclass(frozen=True)
class EpisodeEnd:
    """How the episode ended: its frames, success, why it failed, and its result.json."""

    frames: int
    success: bool
    failure: str | None
    result: dict[str, Any]
    learner_steps: int = 0  # steps a learner drove (DAgger: dagger.py)
    takeovers: int = 0  # spans the expert took back past HG-DAgger's gate


def _doing(env: BuildEnv) -> tuple[tuple[int, int], tuple[int, int]]:
    loop = env.loop
    primitives, bricks = [], []
    for arm in ("left", "right"):
        step = loop.step_of(arm)
        primitives.append(PRIMITIVES.index(step.name) if step is not None else 0)
        task = loop.dispatch.task_of[arm]
        bricks.append(task.brick if task is not None and task.brick is not None else -1)
    return (primitives[0], primitives[1]), (bricks[0], bricks[1])


SECONDS_PER_BRICK = 30.0  # of an episode's default time limit


def step_limit(bricks: int, fps: int) -> int:
    """An episode's default step limit: 30 s a brick and 30 s more, at `fps` (the expert
    takes 10-20 s a brick; docs/evaluation.md). A recording's episodes end there too."""
    return int((SECONDS_PER_BRICK * bricks + SECONDS_PER_BRICK) * fps)


NOISE_PERIOD = 1.0  # s between draws of the noise's offset: a learner's errors hold a while


class JointNoise:
    """DART's noise (Laskey et al. 2017): an offset on the executed joint targets, each joint
    drawn from N(0, `scale`) every NOISE_PERIOD, from the episode's seed (the fingers are
    left alone); of waypoint actions, on each hand's x, y and z (`scale` in metres)."""

    def __init__(self, env: BuildEnv, seed: int, scale: float) -> None:
        self.scale = scale
        self.joints = env.mode.moved
        self.period = max(1, round(NOISE_PERIOD * env.fps))
        self.random = np.random.default_rng([seed, 0xDA27])
        self.offset = np.zeros(len(self.joints))
        self.steps = 0

    def __call__(self, action: np.ndarray) -> np.ndarray:
        """`action` as executed."""
        if self.scale == 0.0:
            return action
        if self.steps % self.period == 0:
            self.offset = self.joints * self.random.normal(0.0, self.scale, len(self.joints))
        self.steps += 1
        return (action + self.offset).astype(np.float32)


def expert_episode(
    env: BuildEnv,
    seed: int,
    cameras: tuple[str, ...],
    on_frame: Callable[[Frame], Any],
    noise: float = 0.0,
    mixer: Mixer | None = None,
) -> EpisodeEnd:
    """Roll the expert out from `reset(seed=seed)` to the end of the episode, a frame each
    environment step (the environment steps at the dataset's rate), at most `step_limit`
    frames, as an evaluation's (and the environment's `linger` after a success); the last is
    done. With `noise`, what is executed is off the expert's action by `JointNoise`, and the frame's
    action is still the expert's: what to do from where the arm really is. With a `mixer`
    (DAgger), a learner drives some spans and the expert labels what it reaches (a learner's
    bad action raises PolicyError). Waypoint labels are led past a move's end
    (lead_labels.py)."""
    led = LeadLabels(env.fps, on_frame, (PRIMITIVES.index("grip"), PRIMITIVES.index("release")))
    obs, _ = env.reset(seed=seed)
    executed = JointNoise(env, seed, noise)
    limit = step_limit(len(env.plan.bricks), env.fps) + round(env.linger * env.fps)
    frames = 0
    while True:
        action = env.expert_action()
        waypoints = env.mode.waypoints(action)  # in the frames of this step, if any
        primitive, brick = _doing(env)  # what the expert's action is for
        state = obs["state"].astype(np.float32)
        environment = environment_state(obs)
        images = env.images(cameras) if cameras else {}
        hands = obs["tools"][:, :3].copy()
        obs, reward, terminated, truncated, info = _step(env, obs, executed(action), mixer)
        truncated = truncated or frames + 1 >= limit
        done = terminated or truncated
        frame = Frame(
            state,
            environment,
            action.astype(np.float32),
            images,
            float(reward),
            done,
            bool(info["is_success"]),
            primitive,
            brick,
        )
        if waypoints is not None:  # led as waypoints, given back in the mode's form
            waypoint, form = waypoints
            led(replace(frame, action=waypoint.astype(np.float32)), hands, form)
        else:
            on_frame(frame)
        frames += 1
        if done:
            failure = info["failure"] or (None if terminated else f"step limit: {limit} steps")
            learner, taken = (mixer.learner_steps, mixer.takeovers) if mixer else (0, 0)
            return EpisodeEnd(frames, info["is_success"], failure, info["result"], learner, taken)


def _step(env: BuildEnv, obs: dict[str, Any], executed: np.ndarray, mixer: Mixer | None) -> Any:
    """`env.step` with the expert's action as `executed`, or a DAgger learner's where the
    `mixer` hands it the span; PolicyError for a learner's action outside the space."""
    if mixer is not None:
        executed = mixer(obs, executed)
    try:
        return env.step(executed)
    except ActionError as err:  # only a learner's action can be outside the space
        raise PolicyError(f"policy: act() gave an {err}") from err
