"""Timers wrapped round named calls for one measured stretch, and the IK's floor: the calls
it makes every control step while mink is the source of its tasks."""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from contextlib import ExitStack, contextmanager
from typing import Any


def ik_floor_calls() -> list[tuple[Any, str]]:
    """What the IK calls on every control step and cannot do without while mink is the source
    of its tasks: the two frame tasks' terms (mink's compiled operations on the IK's MjData,
    `FrameResiduals.write`) and the posture task's, the configuration's kinematics and
    integration, and daqp's solve."""
    import daqp
    import mink

    from ..physics.ik_frames import FrameResiduals

    return [
        (FrameResiduals, "write"),
        (mink.PostureTask, "compute_error"),
        (mink.Configuration, "update"),
        (mink.Configuration, "integrate"),
        (daqp, "solve"),
    ]


@contextmanager
def timed_calls(calls: list[tuple[Any, str]]) -> Iterator[list[float]]:
    """Wrap each `(owner, name)` attribute in a timer while inside; yields the seconds spent in
    them (a call within a timed call counts once), restored on the way out."""
    spent, depth = [0.0], [0]

    def timed(function: Callable[..., Any]) -> Callable[..., Any]:
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            depth[0] += 1
            start = time.perf_counter()
            try:
                return function(*args, **kwargs)
            finally:
                depth[0] -= 1
                if depth[0] == 0:
                    spent[0] += time.perf_counter() - start

        return wrapper

    originals = [(owner, name, getattr(owner, name)) for owner, name in calls]
    for owner, name, function in originals:
        setattr(owner, name, timed(function))
    try:
        yield spent
    finally:
        for owner, name, function in originals:
            setattr(owner, name, function)


@contextmanager
def timed_parts(parts: dict[str, list[tuple[Any, str]]]) -> Iterator[dict[str, float]]:
    """`timed_calls` for several named parts at once, each with its own clock: yields the
    seconds spent in each part's calls (the parts' calls must not call one another)."""
    with ExitStack() as stack:
        clocks = {name: stack.enter_context(timed_calls(calls)) for name, calls in parts.items()}
        spent: dict[str, float] = {}
        try:
            yield spent
        finally:
            spent.update({name: clock[0] for name, clock in clocks.items()})
