"""The expert sets right a brick it let go off its target: once the hand has lifted off it,
the brick is measured where it lies, and one further off than it is told to allow is picked
up again there and set down once more (a hand that jolted while the fingers opened drags a
brick off its place, and nothing learned or scripted is exact)."""

from __future__ import annotations

import math

from ...choices import Arm
from ...core.poses import Pose, symmetric_yaw_error, yaw_of
from ...core.primitives import Step, StepKind, re_place_steps
from ...core.scheduler import Task
from ...physics import names as c
from ...physics.parts import BuildParts

TRIES = 2  # re-places of one brick before it is left as it lies


class RePlacer:
    """Watches each arm's releases in a build and loads a re-place where a brick lies further
    than `across` (m) or turned more than `turned` (rad) off its target."""

    def __init__(self, parts: BuildParts, across: float, turned: float) -> None:
        self.data, self.custody = parts.data, parts.custody
        self.runners = parts.dispatch.runners
        self.config = parts.config
        self._targets = {b.index: b.target.pose for b in parts.plan.bricks}
        self.across, self.turned = across, turned
        self._let_go: dict[Arm, int | None] = {a: None for a in c.ARMS}
        self.tries: dict[int, int] = {}  # re-places loaded, by brick

    def lies(self, brick: int) -> Pose:
        """Where the brick for place `brick` lies now."""
        body = self.custody.handles.brick_body[self.custody.slot_of[brick]]
        x, y, z = (float(v) for v in self.data.xpos[body])
        return Pose(x, y, z, yaw_of(self.data.xmat[body].reshape(3, 3)))

    def off(self, brick: int) -> bool:
        """Whether the brick lies further off its target than allowed."""
        lies, target = self.lies(brick), self._targets[brick]
        across = math.hypot(lies.x - target.x, lies.y - target.y)
        return across > self.across or symmetric_yaw_error(lies.yaw, target.yaw) > self.turned

    def step_done(self, arm: Arm, step: Step, task: Task | None) -> None:
        """Told of each finished step: after a release, the hand's lift off the brick ends
        with the brick measured, and a re-place loaded ahead of whatever the arm does next."""
        if step.kind is StepKind.RELEASE and task is not None:
            self._let_go[arm] = task.brick
            return
        brick, self._let_go[arm] = self._let_go[arm], None
        if brick is None or step.name != "retract" or brick not in self.custody.slot_of:
            return
        if self.tries.get(brick, 0) >= TRIES or not self.off(brick):
            return
        self.tries[brick] = self.tries.get(brick, 0) + 1
        robot = self.config.robot_description
        steps = re_place_steps(
            self.lies(brick),
            self._targets[brick],
            self.config.hand_motion,
            grasp_height=robot.grasp_height,
            yaw_ref=robot.arms[arm].yaw_reference,
            clearance=robot.pick_clearance,
        )
        runner = self.runners[arm]
        runner.load(steps + runner.steps)
