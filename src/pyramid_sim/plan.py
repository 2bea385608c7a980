"""A build plan: structure targets, the spawn pose, and the arm and order of every brick."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .assignment import Assignment, arrange
from .config import SimConfig
from .poses import Pose
from .structures import make_structure


@dataclass(frozen=True)
class Plan:
    structure: str
    layers: int
    spawn: Pose
    bricks: tuple[Assignment, ...]

    def arm_order(self, arm: str) -> list[int]:
        """Build-order indices of the bricks this arm places."""
        return [b.index for b in self.bricks if b.arm == arm]

    def to_json(self) -> dict[str, Any]:
        """The `pyramid-sim plan` document: metres and radians, world frame."""
        return {
            "structure": self.structure,
            "layers": self.layers,
            "spawn": {"position": _xyz(self.spawn), "yaw": round(self.spawn.yaw, 6)},
            "bricks": [
                {
                    "index": b.index,
                    "arm": b.arm,
                    "layer": b.target.layer,
                    "position": _xyz(b.target.pose),
                    "yaw": round(b.target.pose.yaw, 6),
                }
                for b in self.bricks
            ],
        }


def _xyz(pose: Pose) -> list[float]:
    return [round(pose.x, 6), round(pose.y, 6), round(pose.z, 6)]


def make_plan(structure: str, layers: int, config: SimConfig) -> Plan:
    """Targets of the structure, assigned to the arms by the seed's rule."""
    layout = config.layout
    spawn = Pose(
        layout.spawn_xy[0],
        layout.spawn_xy[1],
        layout.table_top_z + config.brick.height / 2,
        layout.spawn_yaw,
    )
    targets = make_structure(structure, layers, config.brick, (spawn.x, spawn.y, spawn.z))
    return Plan(structure, layers, spawn, arrange(targets))
