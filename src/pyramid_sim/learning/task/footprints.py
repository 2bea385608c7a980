"""The structure's footprint marked on the table for the cameras: each target's outline as a
flat tile drawn into the rendered scene only. Nothing is added to the model, so no contact
and the physics is the same bit for bit; a policy that sees can see where to build."""

from __future__ import annotations

import math
from typing import Any

import mujoco
import numpy as np

RGBA = np.array([0.95, 0.85, 0.2, 0.45], dtype=np.float32)  # a translucent yellow
LIFT = 0.0006  # m above the table top: drawn over it, under any brick


def mark(scene: Any, goals: np.ndarray, length: float, width: float, table_top: float) -> None:
    """Add a tile at each goal (x, y, z, yaw) to a renderer's scene, after `update_scene`."""
    for x, y, _, yaw in goals:
        if scene.ngeom >= scene.maxgeom:
            return
        c, s = math.cos(yaw), math.sin(yaw)
        rotation = np.array([c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0])
        mujoco.mjv_initGeom(
            scene.geoms[scene.ngeom],
            mujoco.mjtGeom.mjGEOM_BOX,
            np.array([length / 2, width / 2, 0.0002]),
            np.array([x, y, table_top + LIFT]),
            rotation,
            RGBA,
        )
        scene.ngeom += 1


def draw_goals(env: Any, scene: Any) -> None:
    """The targets' footprint on the table of a rendered scene of `env` (a BuildEnv), if the
    environment marks it."""
    if env.footprints:
        config = env.loop.config
        mark(scene, env.goals, config.brick.length, config.brick.width, config.layout.table_top_z)
