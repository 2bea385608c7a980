"""The zones the arms take turns in: for DE NIRO's lockstep one shared zone over the spawn
spot and the structure; for the overlap schedule the spot and the structure apart."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from .poses import Pose


@dataclass(frozen=True)
class Zone:
    """An axis-aligned box in x and y (all heights) around the spawn spot and the structure."""

    x_min: float
    x_max: float
    y_min: float
    y_max: float

    def contains(self, point: Sequence[float] | np.ndarray) -> bool:
        return self.x_min <= point[0] <= self.x_max and self.y_min <= point[1] <= self.y_max

    def any_inside(self, points: Iterable[Sequence[float]]) -> bool:
        return any(self.contains(p) for p in points)

    def meets(self, other: Zone) -> bool:
        return (
            self.x_min <= other.x_max
            and other.x_min <= self.x_max
            and self.y_min <= other.y_max
            and other.y_min <= self.y_max
        )

    def joined(self, other: Zone) -> Zone:
        """The smallest box around both."""
        return Zone(
            min(self.x_min, other.x_min),
            max(self.x_max, other.x_max),
            min(self.y_min, other.y_min),
            max(self.y_max, other.y_max),
        )


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


def footprint_zone(poses: Sequence[Pose], length: float, width: float, margin: float) -> Zone:
    """The box around the footprints of bricks (`length` x `width`, turned by each pose's
    yaw) at `poses`, plus `margin`."""
    xs, ys = [], []
    for p in poses:
        c, s = abs(math.cos(p.yaw)), abs(math.sin(p.yaw))
        hx, hy = (length * c + width * s) / 2 + margin, (length * s + width * c) / 2 + margin
        xs += [p.x - hx, p.x + hx]
        ys += [p.y - hy, p.y + hy]
    return Zone(min(xs), max(xs), min(ys), max(ys))


def overlap_zones(
    spawn: Pose, targets: Sequence[Pose], length: float, width: float, margin: float
) -> dict[str, Zone]:
    """The overlap schedule's two zones: the spawn spot's and the structure's. Where they
    meet (a structure built round the spot) both are the box around the two, so one arm at a
    time works there, as in the lockstep."""
    spot = footprint_zone([spawn], length, width, margin)
    structure = footprint_zone(targets, length, width, margin)
    if spot.meets(structure):
        spot = structure = spot.joined(structure)
    return {"spot": spot, "structure": structure}


def segment_gap(
    a0: Sequence[float], a1: Sequence[float], b0: Sequence[float], b1: Sequence[float]
) -> float:
    """The least distance in the plane (x, y) between the segments a0-a1 and b0-b1: how close
    two arms reaching from their bases (a0, b0) to their hands (a1, b1) come, seen from above."""
    p, q, r, s = (np.asarray(v, dtype=float)[:2] for v in (a0, a1, b0, b1))

    def to_segment(x: np.ndarray, s0: np.ndarray, s1: np.ndarray) -> float:
        d = s1 - s0
        t = float(np.clip((x - s0) @ d / (d @ d), 0.0, 1.0)) if d.any() else 0.0
        return float(np.linalg.norm(x - s0 - t * d))

    def side(x: np.ndarray, s0: np.ndarray, s1: np.ndarray) -> float:
        return float((s1[0] - s0[0]) * (x[1] - s0[1]) - (s1[1] - s0[1]) * (x[0] - s0[0]))

    if side(p, r, s) * side(q, r, s) < 0 and side(r, p, q) * side(s, p, q) < 0:
        return 0.0  # they cross
    return min(to_segment(p, r, s), to_segment(q, r, s), to_segment(r, p, q), to_segment(s, p, q))


def footprint(pose: Pose, length: float, width: float) -> list[np.ndarray]:
    """The corners, seen from above, of a brick lying at `pose` (its long axis along its yaw)."""
    c, s = math.cos(pose.yaw), math.sin(pose.yaw)
    return [
        np.array([pose.x + c * u - s * v, pose.y + s * u + c * v])
        for u, v in ((length, width), (-length, width), (-length, -width), (length, -width))
        for u, v in [(u / 2, v / 2)]
    ]


def footprint_gap(a: list[np.ndarray], b: list[np.ndarray]) -> float:
    """The least distance in the plane between two convex footprints (corners in order); 0
    where they overlap."""

    def inside(point: np.ndarray, corners: list[np.ndarray]) -> bool:
        signs = [
            (q[0] - p[0]) * (point[1] - p[1]) - (q[1] - p[1]) * (point[0] - p[0])
            for p, q in zip(corners, corners[1:] + corners[:1])
        ]
        return all(s >= 0 for s in signs) or all(s <= 0 for s in signs)

    if inside(a[0], b) or inside(b[0], a):
        return 0.0
    edges_a = list(zip(a, a[1:] + a[:1]))
    edges_b = list(zip(b, b[1:] + b[:1]))
    return min(
        segment_gap(list(p), list(q), list(r), list(s)) for p, q in edges_a for r, s in edges_b
    )
