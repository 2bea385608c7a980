"""Is every pose of a plan within reach? Checked by IK alone, before any physics."""

from __future__ import annotations

import numpy as np

from . import constants as c
from .config import SimConfig
from .errors import ConfigError, UnreachableError
from .ik import DualArmIK
from .plan import Plan, make_plan
from .poses import Pose
from .primitives import clear_pose, pick_steps, place_steps
from .structures import MAX_LAYERS


def plan_poses(plan: Plan, config: SimConfig) -> list[tuple[str, str, Pose]]:
    """(arm, what, pose) of every move a build of `plan` makes."""
    motion = config.motion
    poses = []
    for arm in c.ARMS:
        poses.append((arm, "clear pose", clear_pose(arm, motion)))
        if plan.arm_order(arm):
            for step in pick_steps(plan.spawn, motion):
                if step.pose is not None:
                    poses.append((arm, f"pick {step.name}", step.pose))
    for b in plan.bricks:
        for step in place_steps(b.target.pose, motion):
            if step.pose is not None:
                poses.append((b.arm, f"brick {b.index} {step.name}", step.pose))
    return poses


class ReachChecker:
    """IK reachability of poses, remembered per (arm, pose): sizes of one structure share most."""

    def __init__(self, config: SimConfig) -> None:
        self.config = config
        self.ik = DualArmIK(config, limit_acceleration=False)
        self._known: dict[tuple[str, Pose], str | None] = {}

    def why_not(self, arm: str, pose: Pose) -> str | None:
        """None if the arm reaches the pose from home, else why not."""
        key = (arm, pose)
        if key not in self._known:
            home = np.array(c.HOME_QPOS)
            self.ik.reset(home, home)
            try:
                self.ik.solve(arm, pose)
                self._known[key] = None
            except UnreachableError as err:
                self._known[key] = str(err)
        return self._known[key]

    def check(self, plan: Plan) -> None:
        """Raise UnreachableError naming the first pose of the plan the IK cannot reach."""
        for arm, what, pose in plan_poses(plan, self.config):
            reason = self.why_not(arm, pose)
            if reason is not None:
                raise UnreachableError(f"{what}: {reason}")

    def largest(self, structure: str, below: int = MAX_LAYERS + 1) -> int:
        """The most layers (under `below`) of `structure` whose every pose is reachable."""
        for layers in range(below - 1, 0, -1):
            try:
                self.check(make_plan(structure, layers, self.config))
                return layers
            except UnreachableError:
                continue
        return 0


def require_reachable(plan: Plan, config: SimConfig) -> None:
    """ConfigError (exit 2 at the command line) naming the largest reachable size."""
    checker = ReachChecker(config)
    try:
        checker.check(plan)
    except UnreachableError as err:
        best = checker.largest(plan.structure, below=plan.layers)
        raise ConfigError(
            f"layers: {plan.structure} with {plan.layers} layers is out of reach ({err}); "
            f"the largest reachable is {best} layers"
        ) from None
