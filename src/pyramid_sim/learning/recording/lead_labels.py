"""A waypoint recording's labels, led past a move's end.

The scripted builder's waypoint is where its current move ends, and it stays there after the
hand has arrived, until the builder's own clock moves it on. A policy sees the hand arrived,
not that clock: taught that label it learns a move's end as a place to stand. So a frame whose
hand is within `ARRIVED` of its waypoint is labelled with the next waypoint the builder gives,
when that comes within `LEAD`: one more than `ARRIVED` from it (the closed loop's aim drifts a
little every frame). A grip or a release on the way keeps the label: the hand stands still
while the fingers work. The frames go to the sink in order, `LEAD` later, each label given
back in its action mode's form (an anchored one from the frames its own step saw).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from .frame import Frame

LEAD = 1.0  # s: how far ahead a label may be taken from
ARRIVED = 0.01  # m from its waypoint at which a hand has arrived
FIELDS = 5  # an arm's action: x, y, z, yaw, gap


class LeadLabels:
    """A sink for frames that hands them on to `on_frame`, labels led, `LEAD` later; `still`
    holds the primitive indices during which a label is kept (grip, release)."""

    def __init__(self, fps: int, on_frame: Callable[[Frame], Any], still: tuple[int, ...]) -> None:
        self.window = max(1, round(LEAD * fps))
        self.on_frame = on_frame
        self.still = still
        self.pending: deque[tuple[Frame, np.ndarray, Callable | None]] = deque()

    def __call__(
        self,
        frame: Frame,
        hands: np.ndarray,
        form: Callable[[np.ndarray], np.ndarray] | None = None,
    ) -> None:
        """Take a frame (its action a waypoint), where each hand's tool centre (x, y, z) was
        at it, and what turns its waypoint label into its action mode's (none: as it is)."""
        self.pending.append((frame, np.asarray(hands, dtype=np.float64), form))
        if len(self.pending) > self.window:
            self._emit()
        if frame.done:
            while self.pending:
                self._emit()

    def _emit(self) -> None:
        frame, hands, form = self.pending.popleft()
        action = frame.action.copy()
        for k, hand in enumerate(hands):
            if frame.primitive[k] in self.still:
                continue
            span = slice(FIELDS * k, FIELDS * k + 4)
            label = frame.action[span]
            if np.linalg.norm(hand - label[:3]) >= ARRIVED:
                continue
            for later, _, _ in self.pending:
                if later.primitive[k] in self.still:
                    break
                if np.linalg.norm(later.action[span][:3] - label[:3]) > ARRIVED:
                    action[span] = later.action[span]
                    break
        self.on_frame(replace(frame, action=action if form is None else form(action)))
