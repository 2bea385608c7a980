"""The environment's `action_mode="relative"`: each arm joint's target given as its change from
where the joint is measured at the step's start, the finger gaps as in `joint` mode.

Why: an absolute target asks a learner for the arm's whole posture to a few milliradians
(a 5 mm placement), an output spread over the joints' ranges; a relative one asks only for the
next move, small and near zero while a hand grips or waits, so the same network error is a
far smaller error at the hand (docs/notes/2026-11-28-learning.md has the measurements). The command
a relative
action makes goes through the same motion generator as a joint action.
"""

from __future__ import annotations

import numpy as np
from gymnasium import spaces

from ...physics.loop import BuildLoop
from ..task.layout import Layout
from .joint import JointMode
from .mode import ExpertMove, ModeParts

# rad: the most the expert's relative action moves an arm joint, with the motion generator on
# (`led` says why; docs/notes/2026-11-28-learning.md has the measurements, and why joint actions
# keep the
# IK's whole lead: a held absolute target that near stops the arm)
LEAD = 0.2


def relative_space(layout: Layout) -> spaces.Box:
    """Each joint's change within its range's span either way; the gaps within their travel."""
    low, high = layout.low.copy(), layout.high.copy()
    joints = layout.joints
    span = layout.high[joints] - layout.low[joints]
    low[joints], high[joints] = -span, span
    return spaces.Box(low.astype(np.float32), high.astype(np.float32), dtype=np.float32)


def absolute(action: np.ndarray, state: np.ndarray, layout: Layout) -> np.ndarray:
    """The joint target of a relative `action` taken at `state`, within the joints' ranges."""
    joints = layout.joints
    target = np.array(action, dtype=np.float64)
    target[joints] += state[joints]
    return np.clip(target, layout.low, layout.high)


def relative(target: np.ndarray, state: np.ndarray, layout: Layout) -> np.ndarray:
    """The relative action that commands the joint `target` from `state` (float32)."""
    joints = layout.joints
    action = np.array(target, dtype=np.float64)
    action[joints] -= state[joints]
    return action.astype(np.float32)


def led(target: np.ndarray, state: np.ndarray, layout: Layout, lead: float) -> np.ndarray:
    """The joint `target` brought toward `state` along the line between them, so that no arm
    joint leads its measured position by more than `lead` (rad); the gaps as they are.

    Why: an IK that runs ahead of the arm (the motion generator limits the arm's acceleration,
    the IK does not) asks for targets whose lead grows with the time since a move began, which
    no observation shows; a learner copying them cannot tell how far ahead to aim. A lead held
    within `lead` points the same way and depends only on where the arm is and where it goes."""
    joints = layout.joints
    capped = np.array(target, dtype=np.float64)
    change = capped[joints] - state[joints]
    most = float(np.max(np.abs(change))) if change.size else 0.0
    if most > lead:
        capped[joints] = state[joints] + change * (lead / most)
    return capped


class RelativeMode(JointMode):
    """The joint mode's targets, given as each arm joint's change from where it is measured
    at the step's start; the gaps as they are."""

    def __init__(self, parts: ModeParts) -> None:
        super().__init__(parts)
        self.lead = LEAD if parts.limit_commands else None
        self.space = relative_space(parts.layout)

    def target(self, action: np.ndarray, state: np.ndarray) -> np.ndarray:
        return super().target(absolute(action, state, self.layout), state)

    def held(self, loop: BuildLoop, state: np.ndarray) -> np.ndarray:
        return relative(loop.data.ctrl[loop.handles.ctrl_index], state, self.layout)

    def expert(self, move: ExpertMove) -> np.ndarray:
        """The builder's joint target from where the joints are, no further ahead of them
        than `LEAD` where the motion generator is on."""
        target = super().expert(move)
        if self.lead is not None:
            target = led(target, move.state, self.layout, self.lead)
        return relative(target, move.state, self.layout)
