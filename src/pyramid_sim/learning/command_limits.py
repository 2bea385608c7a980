"""Keeps a policy's joint commands within what the joints can follow before they reach the
servos: each step's change within the joints' speed limits (the margins the build's own IK
keeps) and its change of speed within their acceleration limits. A learned policy is then
scored on the bricks it places rather than ended by its first jerk; what is clamped is counted
and its peak reported, never hidden."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..physics.ik_terms import ARM_VELOCITY_MARGIN, VELOCITY_MARGIN
from ..robots import RobotDescription
from .layout import Layout

ROUNDING = 1e-3  # of a limit: a command at its bound, rounded to float32, is not clamped


def joint_limits(layout: Layout, robot: RobotDescription) -> tuple[np.ndarray, np.ndarray]:
    """Per entry of the command: the speed (rad/s) and acceleration (rad/s^2) it may reach,
    unbounded for the finger gaps (the gripper's force limit governs those)."""
    speed = np.full(layout.size, np.inf)
    acceleration = np.full(layout.size, np.inf)
    k = 0
    for arm in ("left", "right"):
        described = robot.arms[arm]
        for i, (v, a) in enumerate(zip(described.velocity_limits, described.acceleration_limits)):
            speed[k] = (ARM_VELOCITY_MARGIN if i < 4 else VELOCITY_MARGIN) * v
            acceleration[k] = a
            k += 1
        k += 1  # the finger gap
    return speed, acceleration


class CommandLimiter:
    """Clamps each step's command (one every `dt` seconds) to the joints' speed and
    acceleration limits, counting the steps it changed."""

    def __init__(self, speed: np.ndarray, acceleration: np.ndarray, dt: float) -> None:
        self.max_step = speed * dt
        self.max_change = acceleration * dt * dt
        self.dt = dt
        self.last = np.zeros_like(speed)
        self.velocity = np.zeros_like(speed)  # of the last step, per second
        self.clamped = 0  # steps whose command was changed
        self.peak = 0.0  # the largest asked-for over allowed, speed or acceleration

    def reset(self, command: np.ndarray) -> None:
        """A new episode, its joints still at `command`."""
        self.last = command.astype(np.float64).copy()
        self.velocity[:] = 0.0
        self.clamped = 0
        self.peak = 0.0

    def limit(self, command: np.ndarray) -> np.ndarray:
        """The command within the limits: first its change of speed, then its speed."""
        step = command - self.last
        before = self.velocity * self.dt
        change = step - before
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = max(
                float(np.nanmax(np.abs(change) / self.max_change)),
                float(np.nanmax(np.abs(step) / self.max_step)),
            )
        if ratio > 1.0 + ROUNDING:
            self.clamped += 1
            self.peak = max(self.peak, ratio)
            step = before + np.clip(change, -self.max_change, self.max_change)
            step = np.clip(step, -self.max_step, self.max_step)
            command = self.last + step
        self.velocity = step / self.dt
        self.last = command.copy()
        return command


def spline_ramp(
    last: np.ndarray, mid_before: np.ndarray, target: np.ndarray, steps: int
) -> tuple[Callable[[float], np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """The joint command through an environment step of `steps` control steps, at each share
    of it, and the state the next step ramps from. A step one control step long commands its
    target, as the build does; a longer one follows the quadratic B-spline of the targets
    (velocity continuous, half a step behind them): a straight ramp to each target changes the
    velocity at once every step, which doubled the torque peaks (docs/learning.md)."""
    mid = (last + target) / 2
    if steps == 1:
        return (lambda share: target), (target, mid)
    return (lambda s: (1 - s) ** 2 * mid_before + 2 * (1 - s) * s * last + s * s * mid), (
        target,
        mid,
    )
