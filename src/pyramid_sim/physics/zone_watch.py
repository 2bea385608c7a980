"""Which arm is in which zone: read from the arms' zone bodies each control step, told to the
scheduler (which lets an arm in only once the other is out) and counted when both are in one."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol

import mujoco

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
        self._bodies = handles.zone_bodies
        self.violations = 0  # control steps with both arms inside one zone

    def outside(self, arm: Arm, zone: Zone) -> bool:
        """True when none of the arm's zone bodies is inside `zone`."""
        return not zone.any_inside(self._xpos[b] for b in self._bodies[arm])

    def update(self, listener: ZoneListener) -> bool:
        """Tell `listener` where each arm is; True (and counted) if both are in one zone."""
        shared = False
        for name, zone in self.zones.items():
            outside = {a: self.outside(a, zone) for a in c.ARMS}
            for a in c.ARMS:
                listener.report_zone(a, outside[a], name)
            shared = shared or not (outside["left"] or outside["right"])
        self.violations += shared
        return shared
