"""Names of the scene's own parts, spelled once (a robot's are in its preset: `robots/`)."""

from typing import Final

from ..choices import ARMS

ARM_ARM_SENSOR: Final = "arm_arm_contacts"  # contacts between the two arms, counted by MuJoCo
ARM_BODY_SENSOR: Final = "arm_body_contacts_"  # an arm and a body of the robot's own

BRICK_PREFIX: Final = "brick"
TABLE_GEOM: Final = "table_top"
SPAWN_VOLUME: Final = "spawn_volume"  # a brick's box at the spawn spot, grown by the jitter


def brick_name(index: int) -> str:
    """Prefix of the brick with magazine slot `index`."""
    return f"{BRICK_PREFIX}{index:02d}/"


__all__ = [
    "ARMS",
    "ARM_ARM_SENSOR",
    "ARM_BODY_SENSOR",
    "BRICK_PREFIX",
    "SPAWN_VOLUME",
    "TABLE_GEOM",
    "brick_name",
]
