"""One environment step's control steps: the command toward the action's target at each, the
placements and failures they bring, the episode's end where its success or failure comes."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import mink
import numpy as np

from ...choices import HAND_ACTION_MODES
from ...physics.stops import no_motion_reason
from ..task.outcome import episode_failure

if TYPE_CHECKING:
    from .env import BuildEnv

CHECK_EVERY = 10  # control steps between the joint monitor's reductions: a limit broken is
# told within 0.1 s of simulated time


def run_control_steps(
    env: BuildEnv, target: np.ndarray, ramp: Callable[[float], np.ndarray] | None
) -> tuple[str | None, int]:
    """One environment step's control steps toward `target`: why the episode failed, if it
    did, and how many targets newly hold a brick."""
    loop, steps = env.loop, env.control_steps
    failure: str | None = None
    newly = 0
    for k in range(1, steps + 1):
        try:
            failure = loop.apply(command_at(env, target, ramp, k / steps))
        except mink.NoSolutionFound:  # the IK of an ee action: no motion within the limits
            failure = no_motion_reason(loop.data.time)
        newly += env.placing.update(loop)
        env._steps += 1
        failure = failure or episode_failure(loop, env._steps % CHECK_EVERY == 0)
        if failure is not None or (env.placing.count == len(env.plan.bricks) and not env.linger):
            break
    return failure, newly


def command_at(
    env: BuildEnv, target: np.ndarray, ramp: Callable[[float], np.ndarray] | None, share: float
) -> np.ndarray:
    """The command for one control step, `share` through an environment step toward `target`:
    the `ee` mode's IK, the motion generator, or the raw path's spline `ramp`."""
    if env.action_mode in HAND_ACTION_MODES:  # the IK's joints, through the generator
        command = env.ee.command(env.loop, target)
        return env.generator.step(command) if env.limit_commands else command
    return env.generator.step(target) if ramp is None else ramp(share)


def episode_end(env: BuildEnv, failure: str | None) -> tuple[bool, bool, bool]:
    """After a step: whether the build has succeeded, and Gymnasium's terminated and truncated.
    With `linger`, a success ends the episode that long after it, a failure in that time
    taking it back (a recording films the last release and the hands leaving)."""
    time = env.loop.data.time
    success = env.placing.count == len(env.plan.bricks)
    if success and env.built_at is None:
        env.built_at = time
    elif failure is not None and env.built_at is not None:
        success = False  # built, then failed while lingering
    # a step's rounding short of the end counts as at it
    lingering = failure is None and success and time < (env.built_at or 0.0) + env.linger - 1e-9
    truncated = not success and time > env.config.max_sim_time
    return success, not truncated and not lingering and (success or failure is not None), truncated
