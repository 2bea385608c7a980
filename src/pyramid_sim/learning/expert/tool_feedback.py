"""The expert's loop closed on the measured tool and brick: a move is done when the arm's tool
centre is really at its pose, and a slow integral of the remaining error shifts where the IK
aims, so a steady error between command and arm (an offset a policy or DART's noise adds, a
servo's sag) is worked away at the end of each move. Setting a brick down, the error is the
brick's from its target across the table and in yaw (its grip's offset and a turn in the
fingers included), so the brick, not the hand, comes to where it belongs."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ...choices import Arm
from ...core.poses import Pose, wrap_angle, yaw_of
from ...physics import names as c
from ...physics.parts import BuildParts

TIME_CONSTANT = 0.2  # s of the integral: slower than the motion generator and servos' lag
CAP = 0.02  # m: the most the aim is shifted, each axis
TURN_CAP = 0.1  # rad: the most the aim is turned, setting a brick down
PATIENCE = 1.0  # s after a move's path ends before the IK's own error is enough again
PLACING = ("servo", "release")  # the steps that set a carried brick down
REST_SPEED = 0.01  # m/s: a tool slower than this has settled; a lag still closing is no error
# s the tool's velocity and miss are averaged over where a policy's joint targets jitter the
# arm (the joint modes), so the jitter averages out of both rather than reading as motion
JOINT_SMOOTH_TIME = 0.1


class ToolFeedback:
    """Each arm's aim shift (`aim`) and the measured error a move's end is judged by
    (`error_of`), read from a build's data at the arms' tool sites and carried bricks."""

    def __init__(self, parts: BuildParts, smooth_time: float = 0.0) -> None:
        self.data, self.sites = parts.data, parts.handles.tcp_site
        self.smooth_time = smooth_time  # s; 0 reads each control step as it is
        self.dispatch, self.custody = parts.dispatch, parts.custody
        self.dt = parts.config.motion.control_dt
        self._targets = {b.index: b.target.pose for b in parts.plan.bricks}
        self._ik_error = {a: parts.ik.error_of(a) for a in c.ARMS}
        self._half_length = parts.config.brick.length / 2  # a turn's error at the brick's ends
        self.bias = {a: np.zeros(3) for a in c.ARMS}
        self.turn = {a: 0.0 for a in c.ARMS}  # rad, the aim's yaw shift for the brick held
        self._waited = {a: 0.0 for a in c.ARMS}
        self._step: dict[Arm, object] = {a: None for a in c.ARMS}
        self._held: dict[Arm, tuple[int, int] | None] = {a: None for a in c.ARMS}
        self._was = {a: self.data.site_xpos[self.sites[a]].copy() for a in c.ARMS}
        self._velocity = {a: np.zeros(3) for a in c.ARMS}  # m/s, the tool's, smoothed
        self._speed = {a: 0.0 for a in c.ARMS}  # m/s, its norm
        self._smooth_miss = {a: np.zeros(3) for a in c.ARMS}  # m, `_miss`'s, smoothed

    def aim(self, arm: Arm, pose: Pose) -> Pose:
        """Where the IK aims for the arm's tool to come to `pose`."""
        shifted = pose.moved(*self.bias[arm])
        return shifted.with_yaw(shifted.yaw + self.turn[arm]) if self.turn[arm] else shifted

    def _placing(self, arm: Arm) -> tuple[int, int] | None:
        """The (slot, brick) the arm is setting down, if it is."""
        step, held = self.dispatch.runners[arm].current, self._held[arm]
        return held if held is not None and step is not None and step.name in PLACING else None

    def _miss(self, arm: Arm) -> np.ndarray:
        """How far the tool is from its pose (m); setting a brick down, across the table the
        brick's from its target."""
        miss = self.dispatch.runners[arm].pose.position - self.data.site_xpos[self.sites[arm]]
        placing = self._placing(arm)
        if placing is not None:
            slot, brick = placing
            target, body = self._targets[brick], self.custody.handles.brick_body[slot]
            miss[:2] = (target.x, target.y) - self.data.xpos[body][:2]
        return miss

    def _measure(self, arm: Arm, moved: np.ndarray) -> float:
        """The tool's speed (m/s) over the control step it `moved`; where smoothing is asked,
        its velocity's and its miss's averages updated, and the speed the average's."""
        if not self.smooth_time:
            return float(np.linalg.norm(moved)) / self.dt
        share = min(1.0, self.dt / self.smooth_time)
        self._velocity[arm] += (moved / self.dt - self._velocity[arm]) * share
        self._smooth_miss[arm] += (self._miss(arm) - self._smooth_miss[arm]) * share
        return float(np.linalg.norm(self._velocity[arm]))

    def _read_miss(self, arm: Arm) -> np.ndarray:
        """`_miss` as the feedback reads it: smoothed, or as it is now."""
        return self._smooth_miss[arm] if self.smooth_time else self._miss(arm)

    def _turn_miss(self, arm: Arm) -> float:
        """The yaw (rad) the brick being set down lacks to its target's (a brick turned half
        round lies the same); 0 when the arm sets none down."""
        placing = self._placing(arm)
        if placing is None:
            return 0.0
        slot, brick = placing
        rotation = self.data.xmat[self.custody.handles.brick_body[slot]].reshape(3, 3)
        miss = wrap_angle(self._targets[brick].yaw - yaw_of(rotation))
        return miss - math.pi * round(miss / math.pi)

    def update(self) -> None:
        """One control step: each arm meant to stand still (a move's path run, a grip, a
        release until it opens) and at rest has its aim shifted by the integral of its
        measured error."""
        for arm in c.ARMS:
            runner, carry = self.dispatch.runners[arm], self.custody.carry[arm]
            if carry is not None:
                if self._held[arm] != (carry.slot, carry.index):
                    self.turn[arm] = 0.0  # a new grip: its own turn in the fingers
                self._held[arm] = (carry.slot, carry.index)
            elif runner.current is None or runner.current.name not in PLACING:
                self._held[arm] = None
            if runner.current is not self._step[arm]:
                self._step[arm], self._waited[arm] = runner.current, 0.0
            tool = self.data.site_xpos[self.sites[arm]]
            speed = self._speed[arm] = self._measure(arm, tool - self._was[arm])
            self._was[arm] = tool.copy()
            if runner.current is None or not runner.started or runner.time_left() > 0.0:
                continue
            if runner.opening:  # the brick is let go: a hand moving now would only shove it
                continue
            self._waited[arm] += self.dt
            if speed > REST_SPEED:  # still arriving: what is left may be the lag, not an offset
                continue
            gain = self.dt / TIME_CONSTANT
            self.bias[arm] = np.clip(self.bias[arm] + self._read_miss(arm) * gain, -CAP, CAP)
            turned = self.turn[arm] + self._turn_miss(arm) * gain
            self.turn[arm] = float(np.clip(turned, -TURN_CAP, TURN_CAP))

    def error_of(self, arm: Arm) -> Callable[[], float]:
        """The arm's measured position error (m), asked once a move's path has run its
        course; setting a brick down, its turn counts as the distance its ends are off. Past
        PATIENCE the IK's error stands in (an arm held off its pose by contact would never end
        the move otherwise)."""

        def error() -> float:
            if self._waited[arm] > PATIENCE:
                return self._ik_error[arm]()
            if self._speed[arm] > REST_SPEED and self._placing(arm) is not None:
                return math.inf  # a brick let go from a swaying hand is dragged off its place
            ends = self._turn_miss(arm) * self._half_length
            return float(np.sqrt(np.sum(self._read_miss(arm) ** 2) + ends**2))

        return error
