"""The environment's `action_mode="relative"`: each arm joint's target given as its change from
where the joint is measured at the step's start, the finger gaps as in `joint` mode.

Why: an absolute target asks a learner for the arm's whole posture to a few milliradians
(a 5 mm placement), an output spread over the joints' ranges; a relative one asks only for the
next move, small and near zero while a hand grips or waits, so the same network error is a
far smaller error at the hand (docs/learning.md has the measurements). The command a relative
action makes goes through the same motion generator as a joint action.
"""

from __future__ import annotations

import numpy as np
from gymnasium import spaces

from .layout import Layout


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
