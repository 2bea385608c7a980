"""Robot presets: each a `RobotDescription` the physics builds and the planner reads."""

from __future__ import annotations

from ..choices import RobotName
from ..errors import ConfigError
from .baxter import BAXTER
from .description import ArmDescription, RobotDescription
from .panda import PANDA
from .so101 import SO101

PRESETS: dict[str, RobotDescription] = {PANDA.name: PANDA, BAXTER.name: BAXTER, SO101.name: SO101}
DEFAULT_ROBOT: RobotName = PANDA.name


def robot(name: str) -> RobotDescription:
    """The preset called `name`; ConfigError listing the presets otherwise."""
    if name not in PRESETS:
        raise ConfigError(f"robot: unknown {name!r}; accepted {', '.join(PRESETS)}")
    return PRESETS[name]


__all__ = ["DEFAULT_ROBOT", "PRESETS", "ArmDescription", "RobotDescription", "robot"]
