"""What can go wrong with a brick mid-build, as records for result.json: a brick that leaves
the hand between grip and release (a drop), and one that leaves its place in the structure
after release (knocked off). Pure numpy: the physics loop hands in positions."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from ..choices import Arm
from ..config import SimConfig

KNOCK_DISTANCE = 0.02  # m: a placed brick this far from where it was let go was knocked off
MAX_DROPS_PER_BRICK = 3  # then the build stops and says why
GRAVITY = 9.81


@dataclass(frozen=True)
class Drop:
    """A brick that left the hand: which (build order, magazine slot), whose, when, where, in
    which step, and whether it lay on the spawn spot as spawned when the drop was seen."""

    brick: int
    arm: Arm
    slot: int
    time: float
    position: tuple[float, float, float]
    step: str
    on_spot: bool

    def to_dict(self) -> dict[str, Any]:
        doc = asdict(self)
        doc["time"] = round(self.time, 3)
        doc["position"] = [round(v, 4) for v in self.position]
        return doc

    def describe(self) -> str:
        x, y, z = self.position
        return (
            f"brick {self.brick} slipped out of the {self.arm} hand during '{self.step}' at "
            f"t = {self.time:.2f} s, at ({x:.3f}, {y:.3f}, {z:.3f}) m"
        )


@dataclass(frozen=True)
class Knock:
    """A placed brick that moved `moved_mm` from where it was let go."""

    brick: int
    slot: int
    time: float
    position: tuple[float, float, float]
    moved_mm: float

    def to_dict(self) -> dict[str, Any]:
        doc = asdict(self)
        doc["time"] = round(self.time, 3)
        doc["position"] = [round(v, 4) for v in self.position]
        doc["moved_mm"] = round(self.moved_mm, 1)
        return doc


def grip_diagnosis(config: SimConfig) -> str:
    """Why a brick keeps slipping: the friction the two pads can give against its weight."""
    grip, brick = config.gripper, config.brick
    friction = 2 * grip.force * grip.pad_friction
    weight = brick.mass * GRAVITY
    held = (
        f"the grip's friction (2 pads x {grip.force:g} N x {grip.pad_friction:g} = "
        f"{friction:.1f} N)"
    )
    if friction <= weight:
        return (
            f"{held} cannot carry the brick's weight ({weight:.1f} N at {brick.mass:g} kg); "
            f"it holds at most {friction / GRAVITY:.2f} kg standing still"
        )
    return (
        f"{held} exceeds the brick's weight ({weight:.1f} N at {brick.mass:g} kg) by only "
        f"{friction / weight:.1f}x: the carry's accelerations or a knock shook it loose"
    )


class KnockWatch:
    """Placed bricks and where they were let go; reports each one that moves away once."""

    def __init__(self) -> None:
        self.bodies = np.zeros(0, dtype=int)  # an index into MuJoCo's per-body arrays
        self.bricks: list[int] = []
        self.slots: list[int] = []
        self.rest = np.zeros((0, 3))
        self.knocked: set[int] = set()

    def placed(self, brick: int, slot: int, body: int, position: np.ndarray) -> None:
        self.bodies = np.append(self.bodies, body)
        self.bricks.append(brick)
        self.slots.append(slot)
        self.rest = np.vstack([self.rest, position])

    def forget(self, slot: int) -> None:
        """The brick in `slot` is taken up again (to be set right): no longer watched."""
        keep = [i for i, s in enumerate(self.slots) if s != slot]
        self.bodies, self.rest = self.bodies[keep], self.rest[keep]
        self.bricks = [self.bricks[i] for i in keep]
        self.slots = [self.slots[i] for i in keep]
        self.knocked.discard(slot)

    def check(self, xpos: np.ndarray, time: float) -> list[Knock]:
        """New knocks, given every body's position now."""
        if self.bodies.size == 0:
            return []
        moved = np.linalg.norm(xpos[self.bodies] - self.rest, axis=1)
        knocks = []
        for i in np.flatnonzero(moved > KNOCK_DISTANCE):
            if self.slots[i] in self.knocked:
                continue
            self.knocked.add(self.slots[i])
            x, y, z = (float(v) for v in xpos[self.bodies[i]])
            knocks.append(Knock(self.bricks[i], self.slots[i], time, (x, y, z), moved[i] * 1000.0))
        return knocks
