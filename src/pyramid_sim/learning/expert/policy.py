"""The scripted builder as a policy: `act(observation) -> action`, as a learned policy is
driven. It reads the environment's own build (scheduler, primitives, mink IK: the expert is
privileged, not a learner) and the loop closed on it (closure.py): with the motion generator
on, a move is done when the arm's tool is really there (not when the IK says so) and a steady
error is worked away; when somebody else drove the arms since it was last asked, it plans
from where they are. So it can take over an episode midway, and label what to do after a
mistake (DART: `record --noise`). The action mode gives its move as an action."""

from __future__ import annotations

from typing import Any, Protocol

import numpy as np

from ...physics import names as c
from ...physics.loop import BuildLoop
from ..action_modes.mode import ActionMode, ExpertMove


class Driven(Protocol):
    """What the expert reads of the environment it drives (a BuildEnv)."""

    @property
    def loop(self) -> BuildLoop: ...

    @property
    def mode(self) -> ActionMode: ...

    @property
    def control_steps(self) -> int: ...

    @property
    def steps_taken(self) -> int: ...

    def measured_state(self) -> np.ndarray: ...


class ExpertPolicy:
    """The scripted builder's actions in `env` (a BuildEnv, or a wrapper of one): it covers
    each environment step's control steps; once it has built everything and its arms are back,
    it holds them where they are."""

    def __init__(self, env: Any) -> None:
        self.env: Driven = env.unwrapped
        self._loop: BuildLoop | None = None
        self._done = False
        self._asked = -1  # the environment step it was last asked at
        self._last: np.ndarray | None = None  # its last joint command

    def reset(self) -> None:
        """A new episode (also noticed by itself when the environment was reset)."""
        self._loop = self.env.loop
        self._done = False
        self._asked = -1
        self._last = None

    def act(self, observation: Any = None) -> np.ndarray:
        """The action for the environment's next step (the observation is not needed: the
        expert reads the build itself)."""
        env = self.env
        if self._loop is not env.loop:
            self.reset()
        loop = env.loop
        if env.steps_taken != self._asked + 1:
            take_over(loop)  # somebody else drove the arms: on from where they are
        self._asked = env.steps_taken
        if env.mode.hand_poses:  # the mode's own IK follows the builder's poses
            moving = self._move_hands(loop, env.control_steps)
            return env.mode.expert(ExpertMove(loop, None, moving, env.measured_state()))
        joints = self._joint_command(loop, env.control_steps)
        return env.mode.expert(ExpertMove(loop, joints, not self._done, env.measured_state()))

    def _move_hands(self, loop: BuildLoop, steps: int) -> bool:
        """The builder's poses advanced over `steps` control steps: whether it still moves."""
        moving = False
        for _ in range(steps):
            if self._done:
                break
            moving = loop.expert_targets()
            self._done = not moving
        return moving

    def _joint_command(self, loop: BuildLoop, steps: int) -> np.ndarray:
        """The builder's joint command after `steps` control steps of its own IK; once built,
        where it last aimed (not where a noise took it)."""
        command = None
        for _ in range(steps):
            step = None if self._done else loop.expert_command()
            if step is None:
                self._done = True
                break
            command = step.astype(np.float32)  # a copy: the loop rewrites its command
        if command is not None:
            self._last = command
        elif self._last is None:  # built before it moved: hold what is commanded
            self._last = loop.data.ctrl[loop.handles.ctrl_index].astype(np.float32)
        return self._last


def take_over(loop: BuildLoop) -> None:
    """The IK taken to where the arms are, as the expert takes over from whoever drove them:
    it plans from there."""
    loop.ik.reset(*(loop.data.qpos[loop.handles.arm_qpos[a]] for a in c.ARMS))
