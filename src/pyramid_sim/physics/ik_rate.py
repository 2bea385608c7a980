"""The IK's rate through a build: a solve at every control step where accuracy matters, and in
free motion one solve for `MotionConfig.free_ik_interval` control steps, followed step by step
(`DualArmIK.coast`) while both arms stay on the steps it was made for.

Free motion: each arm still (idle, or waiting to start its step) or on a free move with the
span left of its path; the IK itself refuses a span that could bring the arms within its
collision limit's reach. Approach, servo, grip and release run at the full rate.
"""

from __future__ import annotations

from collections.abc import Callable

from ..choices import Arm
from ..config import SimConfig
from ..core.poses import Pose
from ..core.primitives import Step
from . import names as c
from .dispatch import ArmDispatch
from .ik import DualArmIK

# Moves through free space, where one solve may cover several control steps.
FREE_MOVES = frozenset({"hover", "retract", "clear", "standby"})


class IKRate:
    """Solves the IK for the arms' commanded poses at a build's control steps, at the rate
    free motion allows; `solves` counts the solves."""

    def __init__(
        self,
        ik: DualArmIK,
        dispatch: ArmDispatch,
        config: SimConfig,
        aim: Callable[[Arm, Pose], Pose] | None = None,
    ) -> None:
        self.ik, self.dispatch = ik, dispatch
        self.interval = config.motion.free_ik_interval
        self.dt = config.motion.control_dt
        self.solves = 0
        self.aim = aim  # a shift of where the IK aims (a closed loop's)
        self._planned_for: tuple[tuple[Step | None, bool], ...] = ()

    def step(self) -> bool:
        """One control step of the IK: on along the last solve's plan if it still holds, else
        a new solve (True)."""
        if self.ik.planned and self._steps_now() == self._planned_for and self.ik.coast():
            return False
        self.solves += 1
        span = self._span()
        if span > 1 and self._aim_and_step(span):
            self._planned_for = self._steps_now()
        else:
            self._aim_and_step(1)
        return True

    def _steps_now(self) -> tuple[tuple[Step | None, bool], ...]:
        """Each arm's step and whether it has begun: a plan holds while these do."""
        runners = self.dispatch.runners
        return tuple((runners[a].current, runners[a].started) for a in c.ARMS)

    def _span(self) -> int:
        """Control steps the next solve may cover: the interval in free motion, else one."""
        span = self.interval
        if span == 1:
            return 1
        for a in c.ARMS:
            runner = self.dispatch.runners[a]
            step = runner.current
            if step is None or not runner.started:
                continue  # still: it holds its pose until its step starts, and then replans
            if step.name not in FREE_MOVES or runner.time_left() < span * self.dt:
                return 1
        return span if self.ik.may_span(span) else 1

    def _aim_and_step(self, span: int) -> bool:
        """Aim the IK where the arms' paths will be at the end of `span` control steps and
        step over them (False if the IK refused the span)."""
        for a in c.ARMS:
            pose = self.dispatch.runners[a].pose_ahead((span - 1) * self.dt)
            self.ik.set_target(a, pose if self.aim is None else self.aim(a, pose))
        return self.ik.step(span)
