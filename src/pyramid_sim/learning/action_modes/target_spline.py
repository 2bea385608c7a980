"""The raw command path (`limit_commands=False`: no motion generator): a step's joint targets
joined across its control steps by a quadratic B-spline, so the velocity is continuous."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def spline_ramp(
    last: np.ndarray, mid_before: np.ndarray, target: np.ndarray, steps: int
) -> tuple[Callable[[float], np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """The joint command through an environment step of `steps` control steps, at each share
    of it, and the state the next step ramps from. A step one control step long commands its
    target, as the build does; a longer one follows the quadratic B-spline of the targets
    (velocity continuous, half a step behind them): a straight ramp to each target changes the
    velocity at once every step, which doubled the torque peaks
    (docs/notes/2026-11-28-learning.md)."""
    mid = (last + target) / 2
    if steps == 1:
        return (lambda share: target), (target, mid)
    return (lambda s: (1 - s) ** 2 * mid_before + 2 * (1 - s) * s * last + s * s * mid), (
        target,
        mid,
    )
