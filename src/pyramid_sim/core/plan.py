"""A build plan: structure targets, the spawn pose, and the arm and order of every brick."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

from ..choices import ARM_CHOICES, Arm, ArmChoice
from ..config import SimConfig
from ..errors import ConfigError
from .assignment import Assignment, arrange, single_arm
from .poses import Pose, wrap_angle
from .structures import BrickTarget, StructureSpec


@dataclass(frozen=True)
class Plan:
    spec: StructureSpec
    arms: ArmChoice  # both arms (DE NIRO's split) or one alone
    spawn: Pose
    bricks: tuple[Assignment, ...]

    @property
    def structure(self) -> str:
        return self.spec.name

    def arm_order(self, arm: Arm) -> list[int]:
        """Build-order indices of the bricks this arm places."""
        return [b.index for b in self.bricks if b.arm == arm]

    def to_dict(self) -> dict[str, Any]:
        """The `pyramid-sim plan` document: metres and radians, world frame."""
        return {
            "structure": self.structure,
            "size": self.spec.size,
            "arms": self.arms,
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


def moved(
    targets: tuple[BrickTarget, ...], shift: tuple[float, float], turn: float
) -> tuple[BrickTarget, ...]:
    """The targets turned by `turn` (rad) about the centre of their footprint, then shifted;
    unchanged to the bit when both are zero."""
    if turn == 0.0 and shift == (0.0, 0.0):
        return targets
    cx = sum(t.pose.x for t in targets) / len(targets)
    cy = sum(t.pose.y for t in targets) / len(targets)
    cos, sin = math.cos(turn), math.sin(turn)
    return tuple(
        replace(
            t,
            pose=Pose(
                cx + shift[0] + cos * (t.pose.x - cx) - sin * (t.pose.y - cy),
                cy + shift[1] + sin * (t.pose.x - cx) + cos * (t.pose.y - cy),
                t.pose.z,
                wrap_angle(t.pose.yaw + turn),
            ),
        )
        for t in targets
    )


def _xyz(pose: Pose) -> list[float]:
    return [round(pose.x, 6), round(pose.y, 6), round(pose.z, 6)]


def make_plan(spec: StructureSpec, config: SimConfig, arms: ArmChoice = "both") -> Plan:
    """Targets of the structure, assigned to the arms by DE NIRO's rule; with one arm, that
    arm places every brick in the structure's own order (the Brick Manager's single Panda)."""
    if arms not in ARM_CHOICES:
        raise ConfigError(f"arms: unknown {arms!r}; accepted {', '.join(ARM_CHOICES)}")
    layout = config.layout
    spawn = Pose(
        layout.spawn_xy[0],
        layout.spawn_xy[1],
        layout.table_top_z + config.brick.height / 2,
        layout.spawn_yaw,
    )
    # With one arm the structure stands in front of it (the Brick Manager's single Panda built
    # before itself); with two, centred on the spawn spot between them, as DE NIRO's.
    centre_y = spawn.y if arms == "both" else config.robot_description.arms[arms].base[1]
    gaps = (layout.brick_gap, layout.structure_gap)
    targets = spec.targets(config.brick, (spawn.x, centre_y, spawn.z), pickup_y=spawn.y, gaps=gaps)
    targets = moved(targets, layout.structure_shift, layout.structure_turn)
    order = arrange(targets) if arms == "both" else single_arm(targets, arms)
    return Plan(spec, arms, spawn, order)
