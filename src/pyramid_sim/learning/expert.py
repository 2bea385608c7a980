"""The scripted builder as a policy: `act(observation) -> action`, as a learned policy is
driven. It reads the environment's own build (scheduler, primitives, mink IK: the expert is
privileged, not a learner) and plans as if it had driven every step it was asked for, so ask it
once a step."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from ..physics.loop import BuildLoop
    from .env import BuildEnv


class ExpertPolicy:
    """The scripted builder's actions in `env` (a BuildEnv, or a wrapper of one): it covers
    each environment step's control steps; once it has built everything and its arms are back,
    it holds them where they are."""

    def __init__(self, env: Any) -> None:
        self.env: BuildEnv = env.unwrapped
        self._loop: BuildLoop | None = None
        self._done = False

    def reset(self) -> None:
        """A new episode (also noticed by itself when the environment was reset)."""
        self._loop = self.env.loop
        self._done = False

    def act(self, observation: Any = None) -> np.ndarray:
        """The action for the environment's next step (the observation is not needed: the
        expert reads the build itself)."""
        env = self.env
        if self._loop is not env.loop:
            self.reset()
        loop = env.loop
        if env.action_mode == "ee":
            return self._end_effector(loop)
        command = None
        for _ in range(env.control_steps):
            step = None if self._done else loop.expert_command()
            if step is None:
                self._done = True
                break
            command = step.astype(np.float32)  # a copy: the loop rewrites its command
        return env.held_command() if command is None else command

    def _end_effector(self, loop: BuildLoop) -> np.ndarray:
        env = self.env
        moving = False
        for _ in range(env.control_steps):
            if self._done:
                break
            moving = loop.expert_targets()
            self._done = not moving
        if not moving:
            return env.ee.hold(loop).astype(np.float32)
        return env.ee.expert(loop).astype(np.float32)
