"""DAgger (Ross, Gordon and Bagnell 2011): a learned policy drives the arms while the expert
labels every state it reaches, so the data hold the states the learner gets itself into and
what to do there, which the expert's own demonstrations never show.

The expert closes its loop on the measured tools and bricks, so its action is what to do from
where the arms really are; but its own bookkeeping (which brick a hand grips, which it has set
down) follows its own steps. An episode is cut into spans of `SPAN` seconds (a learned chunk's
length); each span is driven by the expert with probability `beta` (DAgger's mixing, drawn
from the episode's seed), else by the learner, its action chunk started afresh at the span's
start, within a bound of the expert's (`bounded`): its hands' poses pulled back to within
`REACH` and `TURN` of where the expert's go, its fingers the expert's, as HG-DAgger's expert
takes over where the learner strays, made continuous. So the expert's bookkeeping stays the
world's. Unbounded, a learner that gripped or set down a brick on its own left the expert's
steps behind the world: a round of 26 six-brick episodes built none, 25 ending on a joint's
torque. Every frame's label is the expert's.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from .policy_calls import policy_call

SPAN = 2.0  # s a driver keeps the arms: a learned chunk of 20 actions at 10 frames a second
REACH = 0.005  # m a hand's pose may stray from the expert's (DART's 5 mm), at DE NIRO's scale
TURN = 0.05  # rad its yaw may
JOINT_REACH = 0.005  # rad a joint's target may, in the joint modes
# a learner's action as executed, given the expert's; None: the expert takes over
Bound = Callable[[np.ndarray, np.ndarray], np.ndarray | None]


def bounded(mode: Any, learner: np.ndarray, expert: np.ndarray, scale: float = 1.0) -> np.ndarray:
    """The learner's action pulled back to within the bound of the expert's, in `mode`'s
    form: each hand's position within `REACH` (times the robot's `scale`) and yaw within
    `TURN` of the expert's waypoint, its fingers the expert's; in a mode of no waypoints,
    each entry that moves an arm within `REACH` or `JOINT_REACH` of the expert's, the rest
    the expert's."""
    ways = mode.waypoints(expert)
    if ways is None:
        reach = REACH * scale if mode.moved_unit == "m" else JOINT_REACH
        out = np.array(expert, dtype=np.float64)
        moved = mode.moved
        out[moved] += np.clip(np.asarray(learner)[moved] - out[moved], -reach, reach)
        return out.astype(np.float32)
    expert_world, form = ways
    learner_world = mode.waypoints(learner)[0]
    out = np.array(expert_world, dtype=np.float64)
    for k in range(len(out) // 5):
        xyz = slice(5 * k, 5 * k + 3)
        out[xyz] += np.clip(learner_world[xyz] - out[xyz], -REACH * scale, REACH * scale)
        turn = math.remainder(float(learner_world[5 * k + 3] - out[5 * k + 3]), 2 * math.pi)
        out[5 * k + 3] += max(-TURN, min(TURN, turn))
    return np.asarray(form(out), dtype=np.float32)


def taken_over(
    mode: Any, learner: np.ndarray, expert: np.ndarray, threshold: float, scale: float = 1.0
) -> np.ndarray | None:
    """HG-DAgger's gate (Kelly et al. 2019): the learner's own action, its fingers the
    expert's, while every hand's position is within `threshold` (times the robot's `scale`)
    of the expert's waypoint; None past it, where the expert takes over. Unlike `bounded`,
    the learner's drift is kept up to the threshold, so the data hold the states it drifts
    into. In a mode of no waypoints, each entry that moves an arm within `threshold` scaled
    as `JOINT_REACH` is to `REACH`."""
    ways = mode.waypoints(expert)
    if ways is None:
        reach = threshold * scale if mode.moved_unit == "m" else threshold * JOINT_REACH / REACH
        moved = mode.moved
        own = np.asarray(learner, dtype=np.float64)
        if np.abs(own[moved] - np.asarray(expert)[moved]).max(initial=0.0) > reach:
            return None
        out = np.array(expert, dtype=np.float64)
        out[moved] = own[moved]
        return out.astype(np.float32)
    expert_world, form = ways
    learner_world = np.array(mode.waypoints(learner)[0], dtype=np.float64)
    for k in range(len(learner_world) // 5):
        xyz = slice(5 * k, 5 * k + 3)
        if np.linalg.norm(learner_world[xyz] - expert_world[xyz]) > threshold * scale:
            return None
        learner_world[5 * k + 4] = expert_world[5 * k + 4]  # the expert's fingers
    return np.asarray(form(learner_world), dtype=np.float32)


class Mixer:
    """Which action is executed at each step of one episode: the expert's, or in the spans
    the learner drives, the learner's for the same observation."""

    def __init__(self, policy: Any, fps: int, seed: int, beta: float, bound: Bound) -> None:
        self.policy, self.beta, self.bound = policy, beta, bound
        self.span = max(1, round(SPAN * fps))
        self.random = np.random.default_rng([seed, 0xDA66E4])
        self.steps = 0
        self.learner = False
        self.learner_steps = 0  # steps the learner drove
        self.takeovers = 0  # spans the expert took back past a gate (`taken_over`)

    def __call__(self, observation: dict[str, Any], expert: np.ndarray) -> np.ndarray:
        """The action executed now, given the observation and the expert's label for it."""
        if self.steps % self.span == 0:
            self.learner = bool(self.random.random() >= self.beta)
            if self.learner:
                _call(self.policy.reset, "reset()")  # a chunk starts with the span
        self.steps += 1
        if not self.learner:
            return expert
        learner = np.asarray(_call(self.policy.act, "act()", observation), dtype=np.float32)
        executed = self.bound(learner, expert)
        if executed is None:  # past the gate: the expert takes the rest of the span
            self.learner = False
            self.takeovers += 1
            return expert
        self.learner_steps += 1
        return executed


def _call(method: Any, what: str, *args: Any) -> Any:
    """A learner's `method(*args)`; PolicyError naming `what` raised what, if it raises."""
    return policy_call(method, f"policy: {what}", *args)
