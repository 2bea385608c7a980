"""An episode's own count and end: its control and environment steps, when it was built, and
whether it has ended; what a step's success or failure makes of it (`end`)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class EpisodeState:
    """One episode's steps and end; `linger` (s) it goes on after its success, `time_limit`
    (s of simulated time) where it is truncated."""

    linger: float
    time_limit: float
    steps: int = 0  # control steps so far
    steps_taken: int = 0  # environment steps so far
    built_at: float | None = None  # sim time (s) of its success
    ended: bool = False

    def end(self, time: float, built: bool, failure: str | None) -> tuple[bool, bool, bool]:
        """After a step at `time` (every target holding a brick: `built`): whether the build
        has succeeded, and Gymnasium's terminated and truncated. With `linger`, a success
        ends the episode that long after it, a failure in that time taking it back (a
        recording films the last release and the hands leaving)."""
        success = built
        if success and self.built_at is None:
            self.built_at = time
        elif failure is not None and self.built_at is not None:
            success = False  # built, then failed while lingering
        # a step's rounding short of the end counts as at it
        lingering = (
            failure is None and success and time < (self.built_at or 0.0) + self.linger - 1e-9
        )
        truncated = not success and time > self.time_limit
        terminated = not truncated and not lingering and (success or failure is not None)
        self.ended = terminated or truncated
        return success, terminated, truncated
