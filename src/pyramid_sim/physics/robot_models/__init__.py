"""The physics side of the robot presets (`robots/`): each builds its robot model into the
scene's MjSpec."""

from __future__ import annotations

from collections.abc import Callable

import mujoco

from ...config import SimConfig
from ...robots import RobotDescription
from .baxter import add_baxter
from .panda import add_panda_pair
from .so101 import add_so101_pair

Builder = Callable[[mujoco.MjSpec, SimConfig, RobotDescription], None]
BUILDERS: dict[str, Builder] = {
    "panda": add_panda_pair,
    "baxter": add_baxter,
    "so101": add_so101_pair,
}


def add_robot(spec: mujoco.MjSpec, config: SimConfig) -> RobotDescription:
    """The configured robot built into `spec`; returns its description."""
    robot = config.robot_description
    BUILDERS[robot.name](spec, config, robot)
    return robot


__all__ = ["BUILDERS", "Builder", "add_robot"]
