"""Is every pose of a plan within reach? Checked by IK alone, before any physics."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from ..choices import Arm, ArmChoice
from ..config import SimConfig
from ..core.plan import Plan, make_plan
from ..core.poses import Pose
from ..core.primitives import clear_pose, pick_steps, place_steps
from ..core.scheduler import other
from ..core.structures import MAX_COURSE, MAX_LAYERS, SIZE_KNOB, STRUCTURES, StructureSpec
from ..errors import ConfigError, UnreachableError
from . import names as c
from .ik import DualArmIK
from .parts import schedule_zones


def plan_poses(plan: Plan, config: SimConfig) -> list[tuple[Arm, str, Pose]]:
    """(arm, what, pose) of every move a build of `plan` makes."""
    motion, robot = config.hand_motion, config.robot_description
    poses: list[tuple[Arm, str, Pose]] = []
    for arm in c.ARMS:
        poses.append((arm, "clear pose", clear_pose(arm, config.robot_description)))
    goals = plan.spec.goals
    for b in plan.bricks:
        label = f"brick {b.index}"
        if goals:
            label += f" (goals row {goals.index(b.target) + 1})"
        grasp, yaw_ref = robot.grasp_height, robot.arms[b.arm].yaw_reference
        for step in pick_steps(
            plan.spawn,
            motion,
            carry_to=b.target.pose,
            grasp_height=grasp,
            yaw_ref=yaw_ref,
            clearance=robot.pick_clearance,
        ):
            if step.pose is not None:
                poses.append((b.arm, f"{label} pick {step.name}", step.pose))
        for step in place_steps(b.target.pose, motion, grasp_height=grasp, yaw_ref=yaw_ref):
            if step.pose is not None:
                poses.append((b.arm, f"{label} {step.name}", step.pose))
    return poses


class ReachChecker:
    """IK reachability of poses, remembered per (arm, pose): sizes of one structure share most;
    and whether each arm, waiting at its clear pose, stands outside the zones the arms take
    turns in (a structure wide enough to reach under a waiting arm cannot be built in turns)."""

    def __init__(self, config: SimConfig) -> None:
        self.config = config
        self.ik = DualArmIK(config, limit_acceleration=False)
        self._known: dict[tuple[str, Pose], str | None] = {}
        self._postures: dict[tuple[str, Pose], np.ndarray] = {}  # the IK's q where it reached
        self.ik.reset_home()
        self._clear_q = {
            a: self.ik.solve(a, clear_pose(a, config.robot_description)) for a in c.ARMS
        }
        self.ik.reset(self._clear_q["left"], self._clear_q["right"])  # as a build starts
        xpos, model = self.ik.configuration.data.xpos, self.ik.model
        self._waiting = {
            a: [(b, xpos[model.body(b).id, :2].copy()) for b in arm.zone_bodies]
            for a, arm in config.robot_description.arms.items()
        }

    def in_the_way(self, plan: Plan) -> str | None:
        """None if every arm that waits while the other works (both, or the one left idle)
        stands at its clear pose outside every zone of the plan's schedule, else which arm's
        body is inside which zone: the zone watch would count both arms in one zone for as
        long as that arm waits, and the build fail."""
        waiting = c.ARMS if plan.arms == "both" else (other(plan.arms),)
        for name, zone in schedule_zones(self.config.schedule, plan, self.config).items():
            for arm in waiting:
                for body, (x, y) in self._waiting[arm]:
                    if zone.contains((x, y)):
                        return (
                            f"the {arm} arm waiting at its clear pose has its {body} inside the "
                            f"{name} zone the arms take turns in, at ({x:.3f}, {y:.3f}) m"
                        )
        return None

    def why_not(self, arm: Arm, pose: Pose) -> str | None:
        """None if the arm reaches the pose from home, else why not. The other arm waits at its
        clear pose, as in a build, where the IK keeps the arms apart."""
        key = (arm, pose)
        if key not in self._known:
            start = {arm: self.ik.home(arm), other(arm): self._clear_q[other(arm)]}
            self.ik.reset(start["left"], start["right"])
            try:
                self.ik.solve(arm, pose)
                self._known[key] = None
                self._postures[key] = self.ik.configuration.q.copy()
            except UnreachableError as err:
                self._known[key] = str(err)
        return self._known[key]

    def posture(self, arm: Arm, pose: Pose) -> np.ndarray:
        """The IK model's joint positions with `arm` at `pose` (solved as `why_not` solves
        it); UnreachableError if it does not reach it."""
        reason = self.why_not(arm, pose)
        if reason is not None:
            raise UnreachableError(reason)
        return self._postures[(arm, pose)]

    def check(self, plan: Plan) -> None:
        """Raise UnreachableError naming an arm that would wait inside a zone (`in_the_way`),
        or a pose of the plan the IK cannot reach: the farthest from its arm's base first,
        where a plan too large fails (its nearer poses are not solved for nothing)."""
        in_the_way = self.in_the_way(plan)
        if in_the_way is not None:
            raise UnreachableError(in_the_way)
        arms = self.config.robot_description.arms
        poses = plan_poses(plan, self.config)
        poses.sort(
            key=lambda p: -float(np.linalg.norm(np.subtract(p[2].position, arms[p[0]].base)))
        )
        for arm, what, pose in poses:
            reason = self.why_not(arm, pose)
            if reason is not None:
                raise UnreachableError(f"{what}: {reason}")

    def largest(
        self, spec: StructureSpec, arms: ArmChoice = "both", below: int | None = None
    ) -> int:
        """The largest value (under `below`) of the structure's size knob (SIZE_KNOB: layers,
        width or towers; the other options as in `spec`) whose every pose is reachable."""
        knob = SIZE_KNOB[spec.name]
        top = MAX_LAYERS if knob == "layers" else MAX_COURSE
        for value in range(min(top, (below or top + 1) - 1), 0, -1):
            try:
                sized = resized(spec, knob, value)
            except ConfigError:
                continue
            try:
                self.check(make_plan(sized, self.config, arms))
                return value
            except UnreachableError:
                continue
        return 0


def resized(spec: StructureSpec, knob: str, value: int) -> StructureSpec:
    """`spec` with its size knob set to `value`, the other options following it as the
    structure declares (core/structures.py: a wall keeps three full courses)."""
    sizes: dict[str, Any] = STRUCTURES[spec.name].resized(spec, value)
    return replace(spec, **sizes)


def held_fixed(spec: StructureSpec) -> str:
    """How `resized` holds the other size options while the knob grows (the reach table)."""
    return STRUCTURES[spec.name].held_fixed(spec)


def require_reachable(plan: Plan, config: SimConfig) -> None:
    """ConfigError (exit 2 at the command line) naming the largest reachable size."""
    checker = ReachChecker(config)
    try:
        checker.check(plan)
    except UnreachableError as err:
        spec = plan.spec
        what = f"{spec.name} ({spec.size_text()}, arms {plan.arms})"
        if spec.name not in SIZE_KNOB:
            raise ConfigError(f"goals: {what} is out of reach: {err}") from None
        knob = SIZE_KNOB[spec.name]
        best = checker.largest(spec, plan.arms, below=getattr(spec, knob))
        # The size as `largest` tried it: the other options can change with the knob (a wall
        # keeps three courses), so the whole size is named.
        largest = (
            f"the largest reachable is {knob} {best} ({resized(spec, knob, best).size_text()})"
            if best
            else f"no {knob} value brings {spec.name} with {held_fixed(spec)} within reach of "
            f"the {config.robot} robot"
        )
        raise ConfigError(f"{knob}: {what} is out of reach ({err}); {largest}") from None


def prepare(spec: StructureSpec, config: SimConfig, arms: ArmChoice = "both") -> Plan:
    """The plan, with every pose checked by IK: raises ConfigError before any physics."""
    plan = make_plan(spec, config, arms)
    require_reachable(plan, config)
    return plan
