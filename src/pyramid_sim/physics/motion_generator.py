"""The arm's motion generator, as a real arm has one between its commands and its servos
(libfranka's rate limiter, MoveIt Servo): each command is a target, and the joints' command
follows it at most at the joints' speed, acceleration and jerk limits, whatever the targets
do. A policy's chunk boundary, its jitter or a slow policy becomes smooth motion rather than
a jolt that shakes a held brick loose. Ruckig computes the time-optimal jerk-limited motion
online, each control cycle, from the command's position, speed and acceleration."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from ruckig import InputParameter, OutputParameter, Result, Ruckig, Synchronization

from ..config import SimConfig
from ..robots import RobotDescription
from .ik_terms import ARM_VELOCITY_MARGIN, VELOCITY_MARGIN

ACCELERATION_SHARE = 0.5  # of the joints' acceleration limits: at full, several joints at once
# asked for more torque than the arm has
JERK_TIME = 0.05  # s from rest to full acceleration: the jerk limit is acceleration / this
# The same where a policy's joint targets reach the generator straight (the joint modes): it
# is then the only filter between a jittering policy and the servos
# (docs/notes/2026-11-28-learning.md)
JOINT_JERK_TIME = 0.15
GRIPPER_SPEED = 2.0  # times the gap's full stroke a close time: fingers closing on a brick
OPENING_SPEED = 10.0  # the same, opening: a hand lets go at once, before a jolt drags the brick


@dataclass(frozen=True)
class MotionLimits:
    """Per entry of the command (each arm's joints, then its finger gap): the most speed
    (rad/s or m/s; `falling` the most downwards), acceleration and jerk the generated command
    may have, and which entries are fingers (they keep their own time, not the arm's)."""

    speed: np.ndarray
    falling: np.ndarray
    acceleration: np.ndarray
    jerk: np.ndarray
    fingers: np.ndarray  # bool

    def __post_init__(self) -> None:
        for name in ("speed", "falling", "acceleration", "jerk"):
            values = getattr(self, name)
            if values.shape != self.speed.shape or not np.all(np.isfinite(values) & (values > 0)):
                raise ValueError(f"motion limits: {name} must be positive and finite, entry-wise")


def motion_limits(
    robot: RobotDescription,
    close_time: float,
    jerk_time: float = JERK_TIME,
    share: float = ACCELERATION_SHARE,
) -> MotionLimits:
    """The robot's limits in the command's order: the joints at the IK's speed margins and
    `share` of their acceleration limits, reached in `jerk_time`, the finger gap closing at
    GRIPPER_SPEED strokes a `close_time` and opening at OPENING_SPEED."""
    speed: list[float] = []
    falling: list[float] = []
    acceleration: list[float] = []
    fingers: list[bool] = []
    stroke = 2 * robot.finger_stroke
    for arm in robot.arms.values():
        for i, (v, a) in enumerate(zip(arm.velocity_limits, arm.acceleration_limits)):
            speed.append((ARM_VELOCITY_MARGIN if i < 4 else VELOCITY_MARGIN) * v)
            falling.append(speed[-1])
            acceleration.append(share * a)
            fingers.append(False)
        speed.append(OPENING_SPEED * stroke / close_time)
        falling.append(GRIPPER_SPEED * stroke / close_time)
        acceleration.append(speed[-1] / jerk_time)
        fingers.append(True)
    most = np.array(acceleration)
    return MotionLimits(
        np.array(speed), np.array(falling), most, most / jerk_time, np.array(fingers)
    )


class MotionGenerator:
    """The command's position, speed and acceleration, stepped `dt` at a time toward each
    target by Ruckig within `limits`; `step(target)` is the next command."""

    def __init__(self, limits: MotionLimits, dt: float) -> None:
        self.limits, self.dt = limits, dt
        n = len(limits.speed)
        self._otg = Ruckig(n, dt)
        self._input = InputParameter(n)
        self._output = OutputParameter(n)
        self._input.max_velocity = limits.speed.tolist()
        self._input.min_velocity = (-limits.falling).tolist()
        self._input.max_acceleration = limits.acceleration.tolist()
        self._input.max_jerk = limits.jerk.tolist()
        # Every joint arrives together (Ruckig's default, said here since it matters): joints
        # each on its own fastest way asked for torque past the limits under a chunked
        # gait (docs/notes/2026-11-28-learning.md). The fingers keep their own time.
        self._input.per_dof_synchronization = [
            Synchronization.No if f else Synchronization.Time for f in limits.fingers
        ]
        self.position = np.zeros(n)
        self.velocity = np.zeros(n)
        self._target = np.zeros(n)
        self.peak_lag = 0.0  # the largest `lag()` asked since the reset

    def reset(self, position: np.ndarray) -> None:
        """At rest at `position` (a new episode's command)."""
        self.position = np.asarray(position, dtype=np.float64).copy()
        self.velocity = np.zeros_like(self.position)
        self._target = self.position.copy()
        self.peak_lag = 0.0
        zeros = [0.0] * len(self.position)
        self._input.current_position = self.position.tolist()
        self._input.current_velocity = zeros
        self._input.current_acceleration = zeros
        self._input.target_velocity = zeros
        self._input.target_acceleration = zeros

    def step(self, target: np.ndarray) -> np.ndarray:
        """The command one `dt` later, heading for `target` to arrive there at rest: whatever
        the targets do, it never overshoots one."""
        if not np.array_equal(target, self._target):
            self._target = np.asarray(target, dtype=np.float64).copy()
            self._input.target_position = self._target.tolist()
        elif np.array_equal(self.position, self._target) and not self.velocity.any():
            return self.position  # arrived and at rest: nothing to compute
        result = self._otg.update(self._input, self._output)
        if result not in (Result.Working, Result.Finished):
            raise RuntimeError(f"motion generator: Ruckig returned {result}")
        self._output.pass_to_input(self._input)
        self.position = np.array(self._output.new_position)
        self.velocity = np.array(self._output.new_velocity)
        return self.position

    def lag(self) -> float:
        """How far the command is from its target now, the largest entry (rad or m); kept in
        `peak_lag` if the largest yet."""
        lag = float(np.max(np.abs(self._target - self.position)))
        self.peak_lag = max(self.peak_lag, lag)
        return lag


def hand_modes_share(robot: RobotDescription) -> float:
    """The share of its joints' acceleration limits the generator behind a hand mode's IK
    uses for `robot`: its own where it sets one (Baxter's, whose shoulder has less torque to
    spare), else ACCELERATION_SHARE."""
    share = robot.hand_modes_acceleration_share
    return ACCELERATION_SHARE if share is None else share


def arm_motion(
    config: SimConfig, jerk_time: float = JERK_TIME, share: float = ACCELERATION_SHARE
) -> MotionGenerator:
    """The motion generator of the settings' robot, stepped at the control rate, its joints
    at `share` of their acceleration limits."""
    limits = motion_limits(config.robot_description, config.gripper.close_time, jerk_time, share)
    return MotionGenerator(limits, config.motion.control_dt)
