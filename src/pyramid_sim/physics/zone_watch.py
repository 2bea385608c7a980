"""Which arm is in which zone: read from the arms' zone bodies each control step, told to the
scheduler (which lets an arm in only once the other is out) and counted when both are in one."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol

import mujoco
import numpy as np

from ..choices import Arm
from ..core.zone import Zone
from . import names as c
from .handles import SceneHandles


class ZoneListener(Protocol):
    """What the zone watch tells: the schedulers' `report_zone`."""

    def report_zone(self, arm: Arm, outside: bool, zone: str) -> None: ...


class ZoneWatch:
    """The schedule's zones against the arms' bodies in `data`."""

    def __init__(
        self, zones: Mapping[str, Zone], data: mujoco.MjData, handles: SceneHandles
    ) -> None:
        self.zones = dict(zones)
        self._xpos = data.xpos
        self._bodies = {a: np.array(handles.zone_bodies[a]) for a in c.ARMS}
        self.violations = 0  # control steps with both arms inside one zone

    def _points(self, arm: Arm) -> list[list[float]]:
        """The arm's zone bodies' x and y, as floats (each test then costs no array lookup)."""
        return self._xpos[self._bodies[arm], :2].tolist()

    def update(self, listener: ZoneListener) -> bool:
        """Tell `listener` where each arm is; True (and counted) if both are in one zone."""
        shared = False
        points = {a: self._points(a) for a in c.ARMS}
        for name, zone in self.zones.items():
            outside = {a: not zone.any_inside(points[a]) for a in c.ARMS}
            for a in c.ARMS:
                listener.report_zone(a, outside[a], name)
            shared = shared or not any(outside.values())
        self.violations += shared
        return shared
