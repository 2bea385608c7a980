"""Damping of a 7-joint arm's twist: joints 1 and 3 turned against each other.

Where the shoulder stands near upright (the Panda's joint 2 near 0) the axes of joints 1 and 3
nearly line up, and turning them against each other barely moves the hand. Under the
acceleration bounds the IK's QP then finds that turn the cheapest way down to a brick and
asks for it at full speed; the servos lag the two joints unequally and the hand swings across
the spot. A damping term on the difference of the two joints' steps makes that turn cost what
it risks, and leaves their turn together (the hand's yaw) and every other joint as it was
(docs/notes/2026-11-28-learning.md, "The arm's twist damped").
"""

from __future__ import annotations

import numpy as np

from ...physics import names as c
from ...physics.handles import dof_addresses
from ...physics.ik import DualArmIK

# Weight of (dq1 - dq3)^2 in the IK's objective, beside its frame tasks' unit costs.
TWIST_DAMPING = 0.05


def damp_twist(ik: DualArmIK, weight: float = TWIST_DAMPING) -> None:
    """Set `weight (dq_a - dq_b)^2` in `ik`'s objective for each arm whose robot names a
    `twist_pair` of joints (nothing for the others); called again, it replaces the last."""
    damping = np.zeros((ik.model.nv, ik.model.nv))
    for arm in c.ARMS:
        description = ik.robot.arms[arm]
        if description.twist_pair is None:
            continue
        names = tuple(description.joints[i] for i in description.twist_pair)
        first, second = dof_addresses(ik.model, names)
        direction = np.zeros(ik.model.nv)
        direction[first], direction[second] = 1.0, -1.0
        damping += weight * np.outer(direction, direction)
    ik.problem.set_extra_damping(damping)
