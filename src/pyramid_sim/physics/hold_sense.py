"""Whether each hand holds a brick, as a real gripper reports it (the Franka Hand's and
Robotiq's object detection): both of its pads touch the same brick, read from the contacts
MuJoCo made. A policy told only the finger gap has to tell a brick held from a hand half
open by a few millimetres of it."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..choices import ARMS


class HoldSense:
    """Each arm's hold (1.0 or 0.0, left first) from a compiled scene's contacts."""

    def __init__(self, model: Any, handles: Any, robot: Any) -> None:
        self.pads = [[model.geom(name).id for name in robot.arms[arm].pads] for arm in ARMS]
        slots = {int(body): slot for slot, body in enumerate(handles.brick_body)}
        self.slot = np.full(model.ngeom, -1)
        for geom in range(model.ngeom):
            self.slot[geom] = slots.get(int(model.geom_bodyid[geom]), -1)

    def __call__(self, data: Any) -> np.ndarray:
        """1.0 for a hand whose two pads touch one brick now."""
        return np.array([float(bool(slots)) for slots in self.slots(data)])

    def slots(self, data: Any) -> list[set[int]]:
        """Each hand's bricks (magazine slots) that both of its pads touch now, left first."""
        n = data.ncon
        if n == 0:
            return [set() for _ in self.pads]
        pairs = np.stack([data.contact.geom1[:n], data.contact.geom2[:n]])
        held = []
        for left_pad, right_pad in self.pads:
            touched = [self._bricks(pairs, pad) for pad in (left_pad, right_pad)]
            held.append(touched[0] & touched[1])
        return held

    def touched(self, data: Any) -> set[int]:
        """The bricks (magazine slots) any pad of either hand touches now: a brick in a hand,
        however it is gripped."""
        n = data.ncon
        if n == 0:
            return set()
        pairs = np.stack([data.contact.geom1[:n], data.contact.geom2[:n]])
        return set().union(*(self._bricks(pairs, pad) for pads in self.pads for pad in pads))

    def _bricks(self, pairs: np.ndarray, pad: int) -> set[int]:
        other = np.concatenate([pairs[1][pairs[0] == pad], pairs[0][pairs[1] == pad]])
        return {int(s) for s in self.slot[other] if s >= 0}
