"""Runs one arm through its list of primitive steps, one control tick at a time.

Pure apart from the numbers it is handed: it turns steps into a tool-centre target pose and a
finger-gap command per tick, and says when the current step and the whole list are done.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from ..choices import Arm
from ..config import SimConfig
from .poses import Pose
from .primitives import Step, StepKind
from .trajectory import Path, plan_path


def grip_gaps(config: SimConfig) -> tuple[float, float]:
    """The gap commands at which the pads press the brick with exactly the grip force, and at
    which they just touch it, squeezing nothing."""
    grip = config.gripper
    squeeze = config.robot_description.squeeze_gap(config.brick.width, grip.force, grip.stiffness)
    return squeeze, squeeze + grip.force / grip.stiffness


@dataclass
class ArmRunner:
    arm: Arm
    config: SimConfig
    pose: Pose  # commanded tool-centre pose
    gap: float  # commanded finger gap (m)
    steps: list[Step] = field(default_factory=list)
    _segment: Path | None = None
    _t: float = 0.0
    _gap_from: float = 0.0
    _opening: float | None = None  # when a release began to open the fingers
    let_go_at_once: bool = False  # a release drops the squeeze at once (a closed loop's)

    @property
    def busy(self) -> bool:
        return bool(self.steps)

    @property
    def current(self) -> Step | None:
        return self.steps[0] if self.steps else None

    @property
    def started(self) -> bool:
        """Whether the current step has begun to run."""
        return self._t > 0.0

    @property
    def open_gap(self) -> float:
        return self.config.robot_description.open_gap()

    @property
    def squeeze_gap(self) -> float:
        """The gap command at which the pads press the brick with exactly the grip force.

        Grip and release ramp between this and open, not closed: the fingers then meet and
        leave the brick slowly (a ramp to zero would cross the brick in its first few ticks
        and shove it, and open at full speed, which tips a brick just let go)."""
        return grip_gaps(self.config)[0]

    @property
    def opening(self) -> bool:
        """Whether a release has begun to open the fingers."""
        return self._opening is not None

    @property
    def contact_gap(self) -> float:
        """The gap command at which the pads just touch the brick, squeezing nothing."""
        return grip_gaps(self.config)[1]

    def load(self, steps: list[Step]) -> None:
        self.steps = list(steps)
        self._start_step()

    def cut_short(self) -> None:
        """Drop the current step where it is: the next starts from the pose commanded now."""
        self.steps.pop(0)
        self._start_step()

    def _start_step(self) -> None:
        self._t = 0.0
        self._opening = None
        self._segment = None
        self._gap_from = self.gap
        step = self.current
        if step is not None and step.kind is StepKind.MOVE:
            assert step.pose is not None
            motion = self.config.hand_motion
            self._segment = plan_path(
                self.pose, step.pose, step.speed, motion.turn_rate, step.transit
            )

    @property
    def path(self) -> Path | None:
        """The current move's path (None for a gripper step or none)."""
        return self._segment

    @property
    def elapsed(self) -> float:
        """Seconds the current step has run."""
        return self._t

    def time_left(self) -> float:
        """Seconds until the current move's path ends (0 for a gripper step or none)."""
        return 0.0 if self._segment is None else max(0.0, self._segment.duration - self._t)

    def pose_ahead(self, seconds: float) -> Pose:
        """The commanded pose `seconds` later along the current move, if it has begun (a step
        not yet begun may be held back: the pose now)."""
        if self._segment is None or seconds == 0.0 or not self.started:
            return self.pose
        return self._segment.at(self._t + seconds)

    def tick(self, dt: float, ik_error: Callable[[], float]) -> Step | None:
        """Advance by dt; returns the step that finished on this tick, if any. `ik_error`
        gives the IK's position error, asked only once a move's path has run its course, and
        before a release opens the fingers."""
        step = self.current
        if step is None:
            return None
        self._t += dt
        grip = self.config.gripper
        if step.kind is StepKind.MOVE:
            assert self._segment is not None
            self.pose = self._segment.at(self._t)
            finished = (
                self._t >= self._segment.duration
                and ik_error() <= self.config.motion.position_tolerance
            )
        elif step.kind is StepKind.GRIP:
            ramp = self._t / grip.close_time
            # Past the ramp the command drops to closed: the force limit keeps the squeeze.
            squeeze = self.squeeze_gap
            self.gap = self._gap_from + (squeeze - self._gap_from) * ramp if ramp < 1 else 0.0
            finished = self._t >= grip.close_time + grip.settle_time
        else:  # RELEASE: hold still until the hand is where it should be, then open
            wait = self.config.motion.settle_before_release
            if self._opening is None and self._t >= wait:
                if ik_error() <= self.config.motion.position_tolerance:
                    self._opening = max(wait, self._t - dt)  # on time, or its first share now
            since = 0.0 if self._opening is None else self._t - self._opening
            ramp = min(1.0, since / grip.close_time)
            start = max(self._gap_from, self.squeeze_gap)
            if self.let_go_at_once:  # the squeeze gone at once, the pads off slowly
                start = max(start, self.contact_gap)
            self.gap = start + (self.open_gap - start) * ramp if ramp > 0 else self._gap_from
            # Done once the fingers are open: no force has to build, unlike a grip's.
            finished = self._opening is not None and since >= grip.close_time
        if not finished:
            return None
        self.steps.pop(0)
        self._start_step()
        return step
