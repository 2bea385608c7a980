"""One IK solve that covers several control steps (free motion, `MotionConfig.free_ik_interval`):
the joint positions of each step, with the velocity ramping from the last solve's to the new
one so every step's change of velocity stays within the acceleration bound. Pure numpy.

Over a span of n steps of dt the ramp moves a joint by dq = early v0 + late v, with
early = (n - 1) dt / 2 and late = (n + 1) dt / 2 (at one step, dq = v dt): the QP solves for
that whole dq, so each bound on v is one on dq.
"""

from __future__ import annotations

import numpy as np


def ramp_split(dt: float, span: int) -> tuple[float, float]:
    """(early, late): the weights of the last and the new velocity in a span's motion."""
    return dt * (span - 1) / 2, dt * (span + 1) / 2


def span_gain(gain: float, span: int) -> float:
    """The task gain for a solve over `span` steps at which a target moving steadily is
    followed as far behind as at one step a solve with `gain` (a lag of (1 - g) / g of a
    solve's motion), so a change of span does not jolt the arms."""
    return span * gain / (1.0 - gain + span * gain)


class SpanPlan:
    """The joint positions at each control step of a span, from `q0` with the velocity
    ramping from `v0` to `v`; hinges and slides only (positions integrate as sums), clamped
    to `ranges` (each coordinate's low and high end)."""

    def __init__(
        self,
        q0: np.ndarray,
        v0: np.ndarray,
        v: np.ndarray,
        dt: float,
        span: int,
        ranges: tuple[np.ndarray, np.ndarray],
    ) -> None:
        share = np.arange(1, span + 1)[:, None] / span
        self.velocities = v0 + (v - v0) * share
        self.rows = q0 + np.cumsum(self.velocities, axis=0) * dt
        low, high = ranges
        np.minimum(np.maximum(self.rows, low, out=self.rows), high, out=self.rows)
        self.row = 0

    @property
    def q(self) -> np.ndarray:
        """The joint positions of the present step."""
        return self.rows[self.row]

    @property
    def done(self) -> bool:
        """Whether the present step is the span's last."""
        return self.row + 1 >= len(self.rows)

    def advance(self) -> bool:
        """On to the next step; False (and nothing done) at the last."""
        if self.done:
            return False
        self.row += 1
        return True
