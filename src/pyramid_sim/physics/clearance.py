"""How close the two arms come: the geoms that stand for each arm, and the closest approach
between them over a build, measured on the physics model.

The exact distance between meshes (`mj_geomDistance`) costs tens of microseconds a pair, and
an arm has 17 collision geoms. Each control step the pairs are first bounded from below by
their bounding spheres; only a pair that could beat the closest approach seen so far is measured
exactly, so after the first step almost none are.
"""

from __future__ import annotations

import mujoco
import numpy as np

from . import names as c

MEASURED_BODIES = c.IK_GUARDED_BODIES + c.FINGER_BODIES
FAR = 1.0  # m: approaches farther than this are not measured exactly


def arm_geoms(model: mujoco.MjModel, arm: str, bodies: tuple[str, ...] | None = None) -> list[int]:
    """Ids of the arm's colliding geoms, on the named bodies only if given."""
    prefix = f"{arm}/"
    wanted = None if bodies is None else {c.prefixed(arm, b) for b in bodies}
    ids = []
    for g in range(model.ngeom):
        body = model.body(model.geom_bodyid[g]).name
        if not body.startswith(prefix) or (wanted is not None and body not in wanted):
            continue
        if model.geom_contype[g] or model.geom_conaffinity[g]:
            ids.append(g)
    return ids


class ArmClearance:
    """The closest approach between the two arms, elbow to fingertips, over every control
    step."""

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        self.model, self.data = model, data
        left, right = (arm_geoms(model, arm, MEASURED_BODIES) for arm in c.ARMS)
        pairs = np.array([(a, b) for a in left for b in right])
        self._g1, self._g2 = pairs[:, 0], pairs[:, 1]
        self._rsum = model.geom_rbound[self._g1] + model.geom_rbound[self._g2]
        self._fromto = np.zeros(6)
        self.closest = FAR  # m
        self.closest_time: float | None = None

    def update(self) -> None:
        xpos = self.data.geom_xpos
        diff = xpos[self._g1] - xpos[self._g2]
        bound = np.sqrt(np.einsum("ij,ij->i", diff, diff)) - self._rsum
        for i in np.flatnonzero(bound < self.closest):
            dist = mujoco.mj_geomDistance(
                self.model, self.data, int(self._g1[i]), int(self._g2[i]), self.closest,
                self._fromto,
            )
            if dist < self.closest:
                self.closest = dist
                self.closest_time = float(self.data.time)
