"""DAgger (Ross, Gordon and Bagnell 2011): a learned policy drives the arms while the expert
labels every state it reaches, so the data hold the states the learner gets itself into and
what to do there, which the expert's own demonstrations never show.

The expert here can label any state: it closes its loop on the measured tools and bricks, so
its action is what to do from where the arms really are. An episode is cut into spans of
`SPAN` seconds (a learned chunk's length); each span is driven by the expert with probability
`beta` (DAgger's mixing, drawn from the episode's seed), else by the learner, its action
chunk started afresh at the span's start. Every frame's label is the expert's.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...errors import ActionError, PolicyError

SPAN = 2.0  # s a driver keeps the arms: a learned chunk of 20 actions at 10 frames a second


class Mixer:
    """Which action is executed at each step of one episode: the expert's, or in the spans
    the learner drives, the learner's for the same observation."""

    def __init__(self, policy: Any, fps: int, seed: int, beta: float) -> None:
        self.policy, self.beta = policy, beta
        self.span = max(1, round(SPAN * fps))
        self.random = np.random.default_rng([seed, 0xDA66E4])
        self.steps = 0
        self.learner = False
        self.learner_steps = 0  # steps the learner drove

    def __call__(self, observation: dict[str, Any], expert: np.ndarray) -> np.ndarray:
        """The action executed now, given the observation and the expert's label for it."""
        if self.steps % self.span == 0:
            self.learner = bool(self.random.random() >= self.beta)
            if self.learner:
                _call(self.policy.reset, "reset()")  # a chunk starts with the span
        self.steps += 1
        if not self.learner:
            return expert
        self.learner_steps += 1
        return np.asarray(_call(self.policy.act, "act()", observation), dtype=np.float32)


def _call(method: Any, what: str, *args: Any) -> Any:
    """A learner's `method(*args)`; PolicyError naming `what` raised what, if it raises."""
    try:
        return method(*args)
    except (ActionError, PolicyError):
        raise
    except (Exception, SystemExit) as err:  # the user's code: one line naming it
        raise PolicyError(f"policy: {what} raised {type(err).__name__}: {err}") from err
