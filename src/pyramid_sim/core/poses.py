"""Top-down gripper poses: a position and a yaw (the hand always points straight down).

Pure numpy, no MuJoCo: geometry, primitives and the scheduler speak in these.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Pose:
    """A brick or tool-centre pose: position (m, world frame) and yaw about z (rad)."""

    x: float
    y: float
    z: float
    yaw: float = 0.0

    @property
    def position(self) -> np.ndarray:
        return np.array([self.x, self.y, self.z])

    def moved(self, dx: float = 0.0, dy: float = 0.0, dz: float = 0.0) -> Pose:
        """The same pose shifted by (dx, dy, dz)."""
        return Pose(self.x + dx, self.y + dy, self.z + dz, self.yaw)

    def with_yaw(self, yaw: float) -> Pose:
        return Pose(self.x, self.y, self.z, yaw)


def wrap_angle(angle: float) -> float:
    """Angle in [-pi, pi)."""
    return (angle + math.pi) % (2 * math.pi) - math.pi


def symmetric_yaw_error(a: float, b: float) -> float:
    """Smallest |a - b| for a brick, which looks the same turned half a turn (rad, [0, pi/2])."""
    d = abs(wrap_angle(a - b)) % math.pi
    return min(d, math.pi - d)


def grasp_yaw(brick_yaw: float, reference: float) -> float:
    """Hand yaw that grips the brick across its width, of the two the nearer `reference`.

    The fingers close along the hand's y axis, so the hand yaw equals the brick yaw modulo pi.
    """
    candidates = (wrap_angle(brick_yaw), wrap_angle(brick_yaw + math.pi))
    # A brick square to the reference is a tie: the larger yaw, so that bricks whose yaws
    # differ by a rounding are gripped alike (not half a turn apart).
    return min(candidates, key=lambda y: (round(abs(wrap_angle(y - reference)), 4), -y))


def yaw_quaternion(yaw: float) -> tuple[float, float, float, float]:
    """A turn by `yaw` about the vertical as a unit quaternion (w, x, y, z): a brick lying flat."""
    return (math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2))


def tcp_quaternion(yaw: float) -> tuple[float, float, float, float]:
    """The downward tool frame turned by `yaw`, Rz(yaw) Rx(pi), as a unit quaternion (w, x, y, z)."""
    return (0.0, math.cos(yaw / 2), math.sin(yaw / 2), 0.0)


def yaw_of(rotation: np.ndarray) -> float:
    """Yaw of a rotation matrix's x axis projected on the ground plane."""
    return math.atan2(rotation[1, 0], rotation[0, 0])


def tilt_of(rotation: np.ndarray) -> float:
    """Angle (rad) between a body's z axis and the world z axis."""
    return math.acos(max(-1.0, min(1.0, abs(rotation[2, 2]))))


def quat_to_matrix(q: np.ndarray) -> np.ndarray:
    """Rotation matrix of a quaternion (w, x, y, z), normalised first."""
    w, x, y, z = q / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )
