"""The expert's closed loop, given to each episode's build loop when it is built
(physics/closure.py): its moves' ends judged and its aim shifted on the measured tool and
brick (tool_feedback.py), its releases letting go at once; for the joint modes, whose targets
a policy's jitter reaches, the tool read over `JOINT_SMOOTH_TIME`, a brick let go off its
target set right (re_place.py) and the arm's twist damped (twist_damping.py)."""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import partial

from ...choices import Arm
from ...core.poses import Pose
from ...core.primitives import Step
from ...core.scheduler import Task
from ...output.result import Tolerances
from ...physics.parts import BuildParts
from .re_place import RePlacer
from .tool_feedback import JOINT_SMOOTH_TIME, ToolFeedback
from .twist_damping import damp_twist

# of each tolerance (across and in yaw) a brick let go may lie off before the expert sets
# it right (the joint modes): one near the tolerance's edge is out at the next small knock
RE_PLACE_MARGIN = 0.7


class ExpertClosure:
    """The loop closed by a `ToolFeedback`, and by a `RePlacer` where one is given."""

    let_go_at_once = True  # a brick set right is let go before a jolt moves it

    def __init__(self, feedback: ToolFeedback, re_placer: RePlacer | None = None) -> None:
        self.feedback, self.re_placer = feedback, re_placer

    def update(self) -> None:
        self.feedback.update()

    def aim(self, arm: Arm, pose: Pose) -> Pose:
        return self.feedback.aim(arm, pose)

    def arrival(self, arm: Arm) -> Callable[[], float]:
        return self.feedback.error_of(arm)

    def step_done(self, arm: Arm, step: Step, task: Task | None) -> None:
        if self.re_placer is not None:
            self.re_placer.step_done(arm, step, task)


def expert_closure(parts: BuildParts, joints: bool, tolerances: Tolerances) -> ExpertClosure:
    """The expert's loop for a build's `parts`; `joints`: a joint mode's (the environment's
    `tolerances` set how far off a brick may lie before it is set right)."""
    feedback = ToolFeedback(parts, JOINT_SMOOTH_TIME if joints else 0.0)
    within = re_place_within(tolerances) if joints else None
    closure = ExpertClosure(feedback, RePlacer(parts, *within) if within is not None else None)
    if joints:  # lagged unequally, a twist swings the hand (twist_damping.py)
        damp_twist(parts.ik)
    return closure


def expert_loop(
    closed: bool, joints: bool, tolerances: Tolerances
) -> Callable[[BuildParts], ExpertClosure] | None:
    """What closes each episode's build loop: the expert's where the motion generator stands
    between it and the servos (`closed`), nothing where the commands go to them raw;
    `joints`: for a joint mode (`expert_closure`)."""
    return partial(expert_closure, joints=joints, tolerances=tolerances) if closed else None


def re_place_within(tolerances: Tolerances) -> tuple[float, float] | None:
    """How far (m) and how turned (rad) a brick let go may lie before the expert sets it
    right: a share of the tolerances the environment judges by."""
    return (
        tolerances.xy_mm / 1000 * RE_PLACE_MARGIN,
        math.radians(tolerances.yaw_deg) * RE_PLACE_MARGIN,
    )
