"""Task dispatch: the scheduler's tasks turned into each arm's primitive steps, and the arms
advanced through them; an arm waits at the shared zone's edge while it may not enter."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import mujoco

from ..choices import Arm
from ..config import SimConfig
from ..core.arm_runner import ArmRunner
from ..core.overlap import OverlapScheduler
from ..core.plan import Plan
from ..core.poses import Pose, grasp_yaw
from ..core.primitives import (
    Step,
    clear_pose,
    clear_steps,
    pick_steps,
    place_steps,
    standby_step,
)
from ..core.scheduler import Action, LockstepScheduler, Task
from ..core.zone import Zone, segment_gap
from . import names as c
from .spawner import Spawner

STANDBY_CLEARANCE = 0.10  # m from a zone's edge to where an arm waits outside it
REACH_GAP = 0.18  # m: arms reaching closer than this (seen from above) do not work at once


class ArmDispatch:
    """Both arms' runners, the task each is running, and the end-of-build retract."""

    def __init__(
        self,
        plan: Plan,
        config: SimConfig,
        spawner: Spawner,
        tcp: dict[str, Pose],
        zones: dict[str, Zone],
        data: mujoco.MjData | None = None,
    ) -> None:
        self.plan, self.config, self.spawner, self.zones = plan, config, spawner, zones
        self.data = data  # where a brick on the spot lies: a pick re-aims at it
        self.robot = config.robot_description
        queues = (plan.arm_order("left"), plan.arm_order("right"))
        self._reach_seen: dict[tuple[Task, Task], bool] = {}
        self.scheduler: OverlapScheduler | LockstepScheduler
        if config.schedule == "overlap":
            self.scheduler = OverlapScheduler(*queues, conflict=self._reach_across)
        else:
            self.scheduler = LockstepScheduler(*queues)
        self.runners = {
            a: ArmRunner(a, config, tcp[a], config.robot_description.open_gap()) for a in c.ARMS
        }
        self.task_of: dict[str, Task | None] = {a: None for a in c.ARMS}
        self._retracting = {a: False for a in c.ARMS}
        self._settle_until: float | None = None
        for a in c.ARMS:
            self.runners[a].load([])

    def step_of(self, arm: Arm) -> Step | None:
        """The primitive step the arm is in (None when idle)."""
        return self.runners[arm].current

    def held(self, arm: Arm) -> bool:
        """Whether the arm must wait before its first move into the shared zone: until the
        other arm is out, and for a pick until a brick lies on the spawn spot."""
        step = self.runners[arm].current
        if step is None or not step.enters_zone or self.runners[arm].started:
            return False
        if not self.scheduler.may_enter(arm):
            return True
        return step.needs_brick and not self.spawner.brick_ready()

    def _reach_across(self, a: Task, b: Task) -> bool:
        """Whether the two arms, reaching from their bases to these tasks' poses, would pass
        within `REACH_GAP` of each other seen from above (asked every control step while an
        arm waits: worked out once a pair)."""
        if (a, b) not in self._reach_seen:
            self._reach_seen[(a, b)] = self._reach_gap(a, b) < REACH_GAP
        return self._reach_seen[(a, b)]

    def _reach_gap(self, a: Task, b: Task) -> float:
        def reach(task: Task) -> tuple[tuple[float, ...], tuple[float, float]]:
            assert task.brick is not None
            pose = (
                self.plan.spawn
                if task.action is Action.PICK
                else self.plan.bricks[task.brick].target.pose
            )
            return self.robot.arms[task.arm].base, (pose.x, pose.y)

        return segment_gap(*reach(a), *reach(b))

    def _may_go(self, arm: Arm, step: Step) -> bool:
        """Whether the arm may go straight on into the zone `step` enters."""
        return self.scheduler.may_enter(arm) and (
            not step.needs_brick or self.spawner.brick_ready()
        )

    def schedule(self, now: float) -> bool:
        """Hand idle arms their next steps; True once the build is over and has settled."""
        if not self.scheduler.finished:
            for a in c.ARMS:
                if not self.runners[a].busy and self.task_of[a] is not self.scheduler.task(a):
                    self._assign(a)
            return False
        for a in c.ARMS:
            if not self._retracting[a] and not self.runners[a].busy:
                self.runners[a].load(clear_steps(a, self.config.hand_motion, self.robot))
                self._retracting[a] = True
        if all(self._retracting.values()) and not any(r.busy for r in self.runners.values()):
            if self._settle_until is None:
                self._settle_until = now + self.config.settle_time
            elif now >= self._settle_until:
                return True
        return False

    def _assign(self, arm: Arm) -> None:
        """Give an idle arm the steps of its task in the current phase."""
        task = self.scheduler.task(arm)
        motion = self.config.hand_motion
        grasp = {
            "grasp_height": self.robot.grasp_height,
            "yaw_ref": self.robot.arms[arm].yaw_reference,
        }
        if task.action in (Action.PICK, Action.PLACE, Action.BUILD):
            assert task.brick is not None
            target = self.plan.bricks[task.brick].target.pose
            quick = self.scheduler.quick_retracts
            steps = []
            if task.action in (Action.PICK, Action.BUILD):
                then = grasp_yaw(target.yaw, grasp["yaw_ref"]) if quick else None
                steps += pick_steps(
                    self.plan.spawn,
                    motion,
                    carry_to=target,
                    then_yaw=then,
                    quick_lift=quick,
                    clearance=self.config.robot_description.pick_clearance,
                    **grasp,
                )
            if task.action in (Action.PLACE, Action.BUILD):
                # A one-jaw hand leaves its fixed jaw against the brick it let go: it lifts
                # clear before it turns (a turn on the way up dragged the brick 3 degrees).
                one_jaw = self.config.robot_description.one_jaw
                then = self._yaw_after(arm, task.brick) if quick and not one_jaw else None
                steps += place_steps(target, motion, then_yaw=then, **grasp)
            if self.scheduler.waits_at_standby and not self._may_go(arm, steps[0]):
                assert steps[0].pose is not None  # a pick or a place begins with a move
                steps.insert(
                    0,
                    standby_step(
                        arm,
                        list(self.zones.values()),
                        self.plan.spawn.x,
                        steps[0].pose,
                        motion,
                        STANDBY_CLEARANCE,
                        [b.target.pose for b in self.plan.bricks[: task.brick]],  # laid by now
                        self.config.brick.length,
                    ),
                )
            self.runners[arm].load(steps)
        elif task.action is Action.CLEAR:
            self.runners[arm].load(clear_steps(arm, motion, self.robot))
        self.task_of[arm] = task

    def _yaw_after(self, arm: Arm, brick: int) -> float:
        """The hand's yaw for the arm's move after placing `brick`: the next pick's, or its
        clear pose's after its last brick."""
        if any(b > brick for b in self.plan.arm_order(arm)):
            return grasp_yaw(self.plan.spawn.yaw, self.robot.arms[arm].yaw_reference)
        return clear_pose(arm, self.robot).yaw

    def advance(
        self,
        arm: Arm,
        ik_error: Callable[[], float],
        on_done: Callable[[Arm, Step, Task | None], None],
    ) -> Pose:
        """One control tick of the arm (unless held); `on_done` hears a finished step before
        the scheduler hears of a finished task. Returns the pose the arm is commanded to."""
        runner = self.runners[arm]
        step = runner.current
        if step is not None and step.name == "standby" and self._may_go(arm, runner.steps[1]):
            runner.cut_short()  # let in on the way: straight on from here
        if runner.busy and not self.held(arm):
            step = runner.current
            if self.spawner.jitter and step is not None and step.needs_brick and not runner.started:
                self._aim_at_brick(arm)
            done = runner.tick(self.config.motion.control_dt, ik_error)
            if done is not None:
                on_done(arm, done, self.task_of[arm])
                if not runner.busy and not self.scheduler.finished:
                    self.scheduler.complete(arm)
        return runner.pose

    def _aim_at_brick(self, arm: Arm) -> None:
        """Re-aim a pick about to start at the brick as it lies on the spot (an imprecise
        feeder sets it off the nominal spot): its moves shifted by the brick's offset and
        turned to its yaw. A precise feeder's brick lies at the nominal spot: nothing to do."""
        slot = self.spawner.current
        if slot is None or self.data is None:
            return
        lies = self.spawner.lies_at(self.data, slot)
        runner, nominal = self.runners[arm], self.plan.spawn
        dx, dy = lies.x - nominal.x, lies.y - nominal.y
        yaw = grasp_yaw(lies.yaw, self.robot.arms[arm].yaw_reference)
        picks = ("hover", "approach", "servo", "retract")
        steps = []
        for k, step in enumerate(runner.steps):
            if k < 5 and step.name in picks and step.pose is not None:
                pose = step.pose.moved(dx, dy)
                step = replace(step, pose=pose if step.name == "retract" else pose.with_yaw(yaw))
            steps.append(step)
        runner.load(steps)

    def dropped(self, arm: Arm, brick: int) -> None:
        """The arm lost its brick: fingers open, off to clear, the brick back in its queue."""
        runner = self.runners[arm]
        runner.gap = runner.open_gap
        runner.load(clear_steps(arm, self.config.hand_motion, self.robot))
        self.scheduler.dropped(arm, brick)
        self.task_of[arm] = self.scheduler.task(arm)
