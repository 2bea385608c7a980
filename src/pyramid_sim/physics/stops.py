"""Why a build was stopped, in words a user can act on."""

from __future__ import annotations

import mujoco
import numpy as np

from ..config import SimConfig
from ..core.scheduler import Action
from . import names as c
from .custody import BrickCustody
from .dispatch import ArmDispatch
from .spawner import Spawner


def warning_reason(data: mujoco.MjData) -> str:
    """The failure for a step that raised MuJoCo warnings (NaN or huge values in the state
    among them: MuJoCo checks qpos, qvel and qacc every step)."""
    raised = [mujoco.mjtWarning(i).name for i in np.flatnonzero(data.warning.number)]
    return (
        f"MuJoCo warning {', '.join(raised)} at t = {data.time:.3f} s: the physics "
        "went wrong (a diverging or overfull step), so the build was stopped"
    )


def no_motion_reason(now: float) -> str:
    """The failure for a control step whose IK found no joint motion within the limits (the
    joints' ranges and speeds and the arms' distance cannot all be kept)."""
    return (
        f"the IK found no joint motion within the arms' limits at t = {now:.3f} s (joint "
        "ranges, speeds and the distance between the arms cannot all be kept), so the build "
        "was stopped"
    )


def stall_reason(
    dispatch: ArmDispatch, custody: BrickCustody, spawner: Spawner, config: SimConfig, now: float
) -> str:
    """Why no arm has finished a move for `stall_time` by `now`: name what they wait for."""
    runners = dispatch.runners
    moving = [a for a in c.ARMS if runners[a].busy and not dispatch.held(a)]
    cause = f"{' and '.join(moving)} arm not reaching its target" if moving else "arms idle"
    for a in (a for a in c.ARMS if runners[a].busy and dispatch.held(a)):
        task = dispatch.task_of[a]
        picking = task is not None and task.action in (Action.PICK, Action.BUILD)
        if picking and dispatch.scheduler.may_enter(a):
            cause = f"{a} arm waiting for the spawn spot to clear (a brick left on or near it)"
        else:
            cause = f"{a} arm waiting for the {dispatch.scheduler.zone_for(a)} zone"
    if custody.drops:
        cause += f"; earlier, {custody.drops[-1].describe()}"
        if spawner.remaining == 0 and custody.needs_brick():
            cause += f" (no spare brick left of {config.spare_bricks})"
    return (
        f"stalled at t = {now:.1f} s: no arm finished a move for {config.stall_time:g} s; {cause}"
    )


def stop_reason(
    dispatch: ArmDispatch,
    custody: BrickCustody,
    spawner: Spawner,
    config: SimConfig,
    now: float,
    last_progress: float,
) -> str | None:
    """Why a build stops at `now`, if it does: its bricks' custody failed, it ran out of
    simulated time, or no arm has finished a step since `last_progress` for `stall_time`."""
    if custody.failure is not None:
        return custody.failure
    if now > config.max_sim_time:
        return f"build did not finish within {config.max_sim_time:g} s of simulated time"
    if now - last_progress > config.stall_time:
        return stall_reason(dispatch, custody, spawner, config, now)
    return None
