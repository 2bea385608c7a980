"""One environment step's control steps: the action mode's command toward the step's target
at each, through the motion generator where it is on, the placements and failures they
bring. Made for each episode from its parts: the loop, the mode, the generator, the
placement watch and the episode's state."""

from __future__ import annotations

import mink
import numpy as np

from ...physics.loop import BuildLoop
from ...physics.motion_generator import MotionGenerator
from ...physics.stops import no_motion_reason
from ..action_modes.mode import ActionMode
from ..task.outcome import PlacementWatch, episode_failure
from .episode_state import EpisodeState

CHECK_EVERY = 10  # control steps between the joint monitor's reductions: a limit broken is
# told within 0.1 s of simulated time


class ControlSteps:
    """`steps` control steps an environment step, `generator` (None: off) between the mode's
    commands and the loop; once every target holds a brick they stop early, unless the
    episode lingers."""

    def __init__(
        self,
        loop: BuildLoop,
        mode: ActionMode,
        generator: MotionGenerator | None,
        placing: PlacementWatch,
        episode: EpisodeState,
        steps: int,
    ) -> None:
        self.loop, self.mode, self.generator = loop, mode, generator
        self.placing, self.episode, self.steps = placing, episode, steps
        self.bricks = len(loop.plan.bricks)

    def run(self, target: np.ndarray) -> tuple[str | None, int]:
        """One environment step's control steps toward `target`: why the episode failed, if
        it did, and how many targets newly hold a brick."""
        loop, steps, episode = self.loop, self.steps, self.episode
        failure: str | None = None
        newly = 0
        for k in range(1, steps + 1):
            try:
                failure = loop.apply(self.command(target, k / steps))
            except mink.NoSolutionFound:  # the IK of a hand mode: no motion within the limits
                failure = no_motion_reason(loop.data.time)
            newly += self.placing.update(loop)
            episode.steps += 1
            failure = failure or episode_failure(loop, episode.steps % CHECK_EVERY == 0)
            if failure is not None or (self.placing.count == self.bricks and not episode.linger):
                break
        return failure, newly

    def command(self, target: np.ndarray, share: float) -> np.ndarray:
        """The command for one control step, `share` through the environment step: the
        mode's, through the motion generator where it is on."""
        command = self.mode.command(self.loop, target, share)
        return command if self.generator is None else self.generator.step(command)
