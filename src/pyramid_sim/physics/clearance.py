"""How close the two arms come: the geoms that stand for each arm, and the closest approach
between them over a build, measured on the physics model.

The exact distance between meshes (`mj_geomDistance`) costs tens of microseconds a pair, and
an arm has 17 collision geoms. Each control step the pairs are first bounded from below by
their bounding spheres; only a pair that could beat the closest approach seen so far is measured
exactly, so after the first step almost none are.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from ..robots import ArmDescription, RobotDescription
from . import names as c

FAR = 10.0  # m, the farthest distance measured exactly: beyond any two arms of the scene


def subtree(model: mujoco.MjModel, root: str) -> set[int]:
    """Ids of the body `root` and every body below it."""
    top = model.body(root).id
    inside = {top}
    for b in range(top + 1, model.nbody):  # a body's id is larger than its parent's
        if model.body_parentid[b] in inside:
            inside.add(b)
    return inside


def colliding_geoms(model: mujoco.MjModel, bodies: set[int]) -> list[int]:
    """Ids of the colliding geoms on `bodies`, in id order."""
    return [
        g
        for g in range(model.ngeom)
        if model.geom_bodyid[g] in bodies and (model.geom_contype[g] or model.geom_conaffinity[g])
    ]


def arm_geoms(
    model: mujoco.MjModel, arm: ArmDescription, bodies: tuple[str, ...] | None = None
) -> list[int]:
    """Ids of the arm's colliding geoms (its root body's subtree), on the named bodies only if
    given."""
    inside = subtree(model, arm.root_body)
    if bodies is not None:
        inside &= {model.body(b).id for b in bodies}
    return colliding_geoms(model, inside)


class ArmClearance:
    """The closest approach between the two arms, elbow to fingertips, over every control
    step."""

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData, robot: RobotDescription) -> None:
        self.model, self.data = model, data
        left, right = (
            arm_geoms(
                model, robot.arms[a], robot.arms[a].guarded_bodies + robot.arms[a].finger_bodies
            )
            for a in c.ARMS
        )
        pairs = np.array([(a, b) for a in left for b in right])
        self._g1, self._g2 = pairs[:, 0], pairs[:, 1]
        self._rsum = model.geom_rbound[self._g1] + model.geom_rbound[self._g2]
        self._fromto = np.zeros(6)
        self.closest = math.inf  # m; the first update measures every pair
        self.closest_time: float | None = None

    def update(self) -> None:
        xpos = self.data.geom_xpos
        diff = xpos[self._g1] - xpos[self._g2]
        bound = np.sqrt(np.einsum("ij,ij->i", diff, diff)) - self._rsum
        for i in np.flatnonzero(bound < self.closest):
            dist = mujoco.mj_geomDistance(
                self.model,
                self.data,
                int(self._g1[i]),
                int(self._g2[i]),
                min(self.closest, FAR),
                self._fromto,
            )
            if dist < self.closest:
                self.closest = dist
                self.closest_time = float(self.data.time)
