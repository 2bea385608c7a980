"""The shared zone both arms must take turns in: the spawn spot and the structure."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Sequence

import numpy as np

from .poses import Pose


@dataclass(frozen=True)
class Zone:
    """An axis-aligned box in x and y (all heights) around the spawn spot and the structure."""

    x_min: float
    x_max: float
    y_min: float
    y_max: float

    def contains(self, point: Sequence[float]) -> bool:
        return self.x_min <= point[0] <= self.x_max and self.y_min <= point[1] <= self.y_max

    def any_inside(self, points: Iterable[np.ndarray]) -> bool:
        return any(self.contains(p) for p in points)


def shared_zone(spawn: Pose, targets: Iterable[Pose], half_extent: float, margin: float) -> Zone:
    """The box around every brick pose (each `half_extent` in radius) plus `margin`."""
    poses = [spawn, *targets]
    pad = half_extent + margin
    return Zone(
        min(p.x for p in poses) - pad,
        max(p.x for p in poses) + pad,
        min(p.y for p in poses) - pad,
        max(p.y for p in poses) + pad,
    )
