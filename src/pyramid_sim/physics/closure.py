"""What closes a build's loop on what is measured, given to the loop when it is built: each
control step's reading, where the IK aims for a pose, when an arm has arrived, what follows a
finished step, and whether a release lets go at once. The loop alone runs open (the scripted
build's own); the expert's closure is the learning side's (learning/expert/closure.py)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol

from ..choices import Arm
from ..core.poses import Pose
from ..core.primitives import Step
from ..core.scheduler import Task


class LoopClosure(Protocol):
    """A closed loop's parts, as `BuildLoop` calls them."""

    let_go_at_once: bool  # a release drops the squeeze at once (each arm's runner)

    def update(self) -> None:
        """One control step's reading, before the arms' primitives advance."""

    def aim(self, arm: Arm, pose: Pose) -> Pose:
        """Where the IK aims for the arm's tool to come to `pose`."""
        ...

    def arrival(self, arm: Arm) -> Callable[[], float]:
        """How far the arm is from its move's end (m), asked as a move ends."""
        ...

    def step_done(self, arm: Arm, step: Step, task: Task | None) -> None:
        """Told of each finished step, before the bricks' custody is."""
