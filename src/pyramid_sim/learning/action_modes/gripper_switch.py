"""The `waypoint` mode's hands: an action's finger gap says open or closed, and the hand runs
the scripted builder's own grip and release (the fingers meet the brick on a ramp, then close
with the grip's force; they leave it on a ramp from where they touch it).

A learned gap that settles between open and closed squeezes the brick with part of the grip's
force, or none, and the brick falls in transit; here such a gap still closes the hand (below
`threshold`, midway between touching the brick and open), as a real gripper's grasp command
closes it whatever speed or width is asked.
"""

from __future__ import annotations

from dataclasses import dataclass

from ...config import SimConfig
from ...core.arm_runner import ArmRunner, grip_gaps
from ...core.primitives import StepKind


@dataclass
class _Hand:
    gap: float  # the finger command now (m)
    closed: bool
    start: float  # the command the current ramp began from
    since: float  # s the current ramp has run


class GripperSwitch:
    """Each arm's finger command from its action's gap, left first."""

    def __init__(self, config: SimConfig, arms: int) -> None:
        self.open = config.robot_description.open_gap()
        self.squeeze, self.contact = grip_gaps(config)
        self.threshold = (self.contact + self.open) / 2
        self.ramp_time = config.gripper.close_time
        self.hands = [_Hand(self.open, False, self.open, self.ramp_time) for _ in range(arms)]

    def reset(self, gaps: list[float]) -> None:
        """The hands as commanded now, their ramps done."""
        self.hands = [_Hand(g, g < self.threshold, g, self.ramp_time) for g in gaps]

    def command(self, arm: int, gap: float, dt: float) -> float:
        """The finger command for one control step of `dt` of an action's `gap`."""
        hand = self.hands[arm]
        close = gap < self.threshold
        if close != hand.closed:
            hand.closed, hand.since = close, 0.0
            hand.start = hand.gap if close else max(hand.gap, self.contact)
        hand.since += dt
        ramp = min(1.0, hand.since / self.ramp_time)
        if close:  # past the ramp, closed: the force limit keeps the squeeze
            hand.gap = hand.start + (self.squeeze - hand.start) * ramp if ramp < 1 else 0.0
        else:
            hand.gap = hand.start + (self.open - hand.start) * ramp
        return hand.gap

    def label(self, runner: ArmRunner) -> float:
        """The gap an action asks for to do what the scripted arm's hand does now: closed
        (0) from a grip's start until a release opens the fingers, else open."""
        step = runner.current
        if step is not None and step.kind is StepKind.GRIP:
            closed = True
        elif step is not None and step.kind is StepKind.RELEASE:
            closed = not runner.opening
        else:
            closed = runner.gap < self.threshold
        return 0.0 if closed else self.open

    def held(self, arm: int) -> float:
        """The gap an action asks for to keep the hand as it is."""
        return 0.0 if self.hands[arm].closed else self.open
