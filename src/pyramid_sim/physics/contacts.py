"""The friction MuJoCo gives a contact between two geoms, from the compiled model: the higher
priority geom's if their priorities differ, else the larger of the two (per component)."""

from __future__ import annotations

import mujoco
import numpy as np

from ..robots import RobotDescription
from . import names as c
from .handles import SceneHandles


def mixed_friction(model: mujoco.MjModel, g1: int, g2: int) -> np.ndarray:
    """Sliding, torsional and rolling friction of a contact between geoms g1 and g2."""
    p1, p2 = model.geom_priority[g1], model.geom_priority[g2]
    if p1 != p2:
        return model.geom_friction[g1 if p1 > p2 else g2].copy()
    return np.maximum(model.geom_friction[g1], model.geom_friction[g2])


def contact_frictions(
    model: mujoco.MjModel, handles: SceneHandles, robot: RobotDescription
) -> dict[str, float]:
    """The sliding friction of each kind of contact a brick makes: with another brick, with
    the table, and with a finger pad."""
    brick = [int(model.body_geomadr[b]) for b in (handles.brick_body[0], handles.brick_body[-1])]
    table = model.geom(c.TABLE_GEOM).id
    pad = model.geom(robot.arms[c.ARMS[0]].pads[0]).id
    pairs = {"brick_brick": brick, "brick_table": (brick[0], table), "pad_brick": (pad, brick[0])}
    return {kind: float(mixed_friction(model, *pair)[0]) for kind, pair in pairs.items()}
