"""Whether bricks can stand where a plan puts them: no two interpenetrate, and each rests on the
table or stands stably on bricks placed before it. Pure numpy, no MuJoCo.

Bricks only turn about z, so each is an oriented rectangle in the xy plane times a z interval:
two boxes are apart when a separating axis exists among the four edge normals of the two
rectangles and z (the separating axis test). The rule for support, and why the pyramid needs
a hull rather than a union, is in docs/structures.md ("When a brick is supported").
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from ..config import BrickConfig
from .poses import Pose

TOLERANCE = 0.001  # m: overlap allowed between two boxes, and the gap a resting face may have
MIN_CONTACT_AREA = TOLERANCE**2  # m^2: faces meeting along a line (or less) support nothing
_EPS = 1e-9


def footprint(pose: Pose, brick: BrickConfig) -> np.ndarray:
    """The brick's four corners in the xy plane, counter-clockwise, (4, 2) metres."""
    c, s = np.cos(pose.yaw), np.sin(pose.yaw)
    along, across = np.array([c, s]), np.array([-s, c])
    half_l, half_w = brick.length / 2, brick.width / 2
    signs = ((1, 1), (-1, 1), (-1, -1), (1, -1))
    return np.array([[pose.x, pose.y] + a * half_l * along + b * half_w * across for a, b in signs])


def overlap_depth(a: Pose, b: Pose, brick: BrickConfig) -> float:
    """How deep two bricks' boxes interpenetrate (m): the smallest overlap of their projections
    over the separating axes (the rectangles' edge normals and z). Zero or less when they only
    touch or stand apart, so a plan's joints and stacked faces are never overlaps."""
    depth = brick.height - abs(a.z - b.z)  # the z axis
    fa, fb = footprint(a, brick), footprint(b, brick)
    for pose in (a, b):
        c, s = np.cos(pose.yaw), np.sin(pose.yaw)
        for axis in (np.array([c, s]), np.array([-s, c])):
            pa, pb = fa @ axis, fb @ axis
            depth = min(depth, min(pa.max(), pb.max()) - max(pa.min(), pb.min()))
    return float(depth)


def _cross(u: np.ndarray, v: np.ndarray) -> float:
    return float(u[0] * v[1] - u[1] * v[0])


def clip_convex(subject: np.ndarray, clip: np.ndarray) -> np.ndarray:
    """The intersection of two convex counter-clockwise polygons (Sutherland-Hodgman), (n, 2);
    empty (0, 2) when they do not meet."""
    out = [p for p in subject]
    for k in range(len(clip)):
        a, edge = clip[k], clip[(k + 1) % len(clip)] - clip[k]
        points, out = out, []
        for i, p in enumerate(points):
            q = points[i - 1]
            dp, dq = _cross(edge, p - a), _cross(edge, q - a)
            if (dp >= -_EPS) != (dq >= -_EPS):
                out.append(q + (p - q) * (dq / (dq - dp)))
            if dp >= -_EPS:
                out.append(p)
        if not out:
            break
    return np.array(out, dtype=float).reshape(-1, 2)


def polygon_area(polygon: np.ndarray) -> float:
    """Area (m^2) of a simple polygon, by the shoelace formula; 0 for fewer than 3 points."""
    if len(polygon) < 3:
        return 0.0
    x, y = polygon[:, 0], polygon[:, 1]
    return float(abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))) / 2)


def convex_hull(points: np.ndarray) -> np.ndarray:
    """The convex hull of points in the plane, counter-clockwise (Andrew's monotone chain)."""
    pts = sorted({(round(float(x), 12), round(float(y), 12)) for x, y in points})
    if len(pts) < 3:
        return np.array(pts, dtype=float).reshape(-1, 2)

    def half(seq: list[tuple[float, float]]) -> list[tuple[float, float]]:
        chain: list[tuple[float, float]] = []
        for p in seq:
            while (
                len(chain) >= 2
                and _cross(np.subtract(chain[-1], chain[-2]), np.subtract(p, chain[-2])) <= _EPS
            ):
                chain.pop()
            chain.append(p)
        return chain

    lower, upper = half(pts), half(pts[::-1])
    return np.array(lower[:-1] + upper[:-1], dtype=float)


def distance_outside(point: np.ndarray, polygon: np.ndarray) -> float:
    """How far (m) a point lies outside a convex counter-clockwise polygon: 0 inside or on it."""
    n = len(polygon)
    edges = [(polygon[k], polygon[(k + 1) % n]) for k in range(n)]
    if n >= 3 and all(_cross(b - a, point - a) >= -_EPS for a, b in edges):
        return 0.0
    gaps = []
    for a, b in edges:
        ab = b - a
        t = 0.0 if not ab.any() else float(np.clip(np.dot(point - a, ab) / np.dot(ab, ab), 0, 1))
        gaps.append(float(np.linalg.norm(point - (a + t * ab))))
    return min(gaps)


@dataclass(frozen=True)
class Fault:
    """Why brick `index` (build order) cannot be placed: it overlaps `others[0]` by `distance`,
    floats `distance` above the table, or would tip with its centre `distance` outside the
    support of `others` (the bricks under it)."""

    kind: str  # "overlap", "floats" or "tips"
    index: int
    others: tuple[int, ...]
    distance: float  # m

    def describe(self, label: Callable[[int], str] = lambda i: f"brick {i}") -> str:
        """One sentence naming the bricks by `label` (a goal file's rows, say) and the rule."""
        mm, tol = self.distance * 1000, TOLERANCE * 1000
        names = " and ".join(label(i) for i in self.others)
        if self.kind == "overlap":
            return (
                f"{names} and {label(self.index)}: the bricks overlap by {mm:.1f} mm; "
                f"accepted at most {tol:g} mm"
            )
        if self.kind == "floats":
            return (
                f"{label(self.index)}: the brick floats, {mm:.0f} mm above the table with no "
                f"brick placed before it under it; accepted resting on the table or on the "
                f"top of bricks placed before it, within {tol:g} mm"
            )
        return (
            f"{label(self.index)}: the brick would tip, its centre {mm:.1f} mm outside its "
            f"support on {names}; accepted a centre over the convex hull of where it "
            "touches the bricks under it"
        )


def _contacts(poses: Sequence[Pose], i: int, brick: BrickConfig) -> list[tuple[int, np.ndarray]]:
    """The bricks before brick i whose top face meets its bottom face, with each contact."""
    below = footprint(poses[i], brick)
    found = []
    for j in range(i):
        if abs(poses[j].z + brick.height - poses[i].z) > TOLERANCE:
            continue
        patch = clip_convex(footprint(poses[j], brick), below)
        if polygon_area(patch) > MIN_CONTACT_AREA:
            found.append((j, patch))
    return found


def first_fault(poses: Sequence[Pose], brick: BrickConfig, rest_z: float) -> Fault | None:
    """The first brick of a build order (`poses`, resting centres) that overlaps one placed
    before it, floats, or would tip; None when every brick can stand. `rest_z` is the centre
    height of a brick lying on the table."""
    reach = float(np.hypot(brick.length, brick.width))
    for i, pose in enumerate(poses):
        for j in range(i):
            other = poses[j]
            apart = np.hypot(other.x - pose.x, other.y - pose.y) >= reach
            if apart or abs(other.z - pose.z) >= brick.height:
                continue  # too far apart to touch: skip the exact test
            depth = overlap_depth(other, pose, brick)
            if depth > TOLERANCE:
                return Fault("overlap", i, (j,), depth)
        if abs(pose.z - rest_z) <= TOLERANCE:
            continue  # on the table
        under = _contacts(poses, i, brick)
        if not under:
            return Fault("floats", i, (), pose.z - rest_z)
        hull = convex_hull(np.vstack([patch for _, patch in under]))
        outside = distance_outside(np.array([pose.x, pose.y]), hull)
        if outside > _EPS:
            return Fault("tips", i, tuple(j for j, _ in under), outside)
    return None
