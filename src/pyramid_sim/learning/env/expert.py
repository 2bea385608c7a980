"""The scripted builder as a policy: `act(observation) -> action`, as a learned policy is
driven. It reads the environment's own build (scheduler, primitives, mink IK: the expert is
privileged, not a learner) and closes the loop on it: with the motion generator on, a move is
done when the arm's tool is really there (not when the IK says so) and a steady error is
worked away (learning/expert/tool_feedback.py); when somebody else drove the arms since it was last
asked, it plans from where they are. So it can take over an episode midway, and label
what to do after a mistake (DART: `record --noise`)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ...choices import HAND_ACTION_MODES
from ...physics import names as c
from .anchored_actions import hand_action
from .relative_actions import led, relative

if TYPE_CHECKING:
    from ...physics.loop import BuildLoop
    from .env import BuildEnv

# rad: the most a relative action moves an arm joint, with the motion generator on
# (relative_actions.led says why; docs/learning.md has the measurements, and why joint
# actions keep the IK's whole lead: a held absolute target that near stops the arm)
LEAD = 0.2


class ExpertPolicy:
    """The scripted builder's actions in `env` (a BuildEnv, or a wrapper of one): it covers
    each environment step's control steps; once it has built everything and its arms are back,
    it holds them where they are."""

    def __init__(self, env: Any) -> None:
        self.env: BuildEnv = env.unwrapped
        self._loop: BuildLoop | None = None
        self._done = False
        self._asked = -1  # the environment step it was last asked at
        self._last: np.ndarray | None = None  # its last joint action

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
        if env.action_mode in HAND_ACTION_MODES:
            return self._end_effector(loop)
        command = None
        for _ in range(env.control_steps):
            step = None if self._done else loop.expert_command()
            if step is None:
                self._done = True
                break
            command = step.astype(np.float32)  # a copy: the loop rewrites its command
        if command is not None:
            self._last = command
        elif self._last is None:  # built before it moved: hold what is commanded
            loop_ctrl = loop.data.ctrl[loop.handles.ctrl_index]
            self._last = loop_ctrl.astype(np.float32)
        # once built, where it last aimed (not where a noise took it)
        if env.action_mode == "relative":  # the target, from where the joints are ...
            state = env.measured_state()
            if env.limit_commands:  # ... no further ahead of them than LEAD
                return relative(led(self._last, state, env.layout, LEAD), state, env.layout)
            return relative(self._last, state, env.layout)
        return self._last

    def _end_effector(self, loop: BuildLoop) -> np.ndarray:
        env = self.env
        moving = False
        for _ in range(env.control_steps):
            if self._done:
                break
            moving = loop.expert_targets()
            self._done = not moving
        if not moving and env.action_mode == "ee":  # a waypoint stays where the build ended
            return env.ee.hold(loop).astype(np.float32)
        return hand_action(env.action_mode, env.ee.expert(loop), env.anchors)


def take_over(loop: BuildLoop) -> None:
    """The IK taken to where the arms are, as the expert takes over from whoever drove them:
    it plans from there."""
    loop.ik.reset(*(loop.data.qpos[loop.handles.arm_qpos[a]] for a in c.ARMS))
