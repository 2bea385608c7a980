"""The expert perturbed the way a learned policy errs, to measure how forgiving the command
path is: white noise on the joint targets every step, each action held for some steps and
then a jump (a chunked policy's gait), a constant offset redrawn every second (a chunk
boundary), or a delay of some steps. Pure: numpy only."""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

import numpy as np

from ...errors import ConfigError

KINDS = ("none", "noise", "hold", "offset", "delay")
OFFSET_PERIOD = 25  # steps between an offset's draws: a second at 25 fps


@dataclass(frozen=True)
class Perturbation:
    """`kind` of KINDS; `amount` in rad for noise and offset (each joint's standard
    deviation; in m with `metres`, each hand position's, for waypoint actions), in steps for
    hold and delay."""

    kind: str
    amount: float
    metres: bool = False

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ConfigError(f"perturbation: unknown {self.kind!r}; accepted {', '.join(KINDS)}")
        if self.kind in ("hold", "delay") and not (
            float(self.amount).is_integer() and self.amount >= 1
        ):
            raise ConfigError(
                f"perturbation: {self.kind} {self.amount!r}; accepted 1 or more steps"
            )
        if not 0 <= self.amount <= 1e4:
            raise ConfigError(f"perturbation: {self.amount!r}; accepted 0 to 10000")

    @property
    def text(self) -> str:
        if self.kind == "none":
            return "none"
        small = " mm" if self.metres else " mrad"
        unit = small if self.kind in ("noise", "offset") else " steps"
        value = self.amount * 1000 if unit == small else self.amount
        return f"{self.kind} {value:g}{unit}"


class Perturber:
    """Turns each step's action into the perturbed one, for one episode drawn from `seed`;
    the finger gaps (`joints` False) are left alone."""

    def __init__(self, perturbation: Perturbation, joints: np.ndarray, seed: int) -> None:
        self.p, self.joints = perturbation, joints
        self.random = np.random.default_rng([seed, 0x9E27])
        self.steps = 0
        self.held: np.ndarray | None = None
        self.offset = np.zeros(len(joints))
        self.queue: deque[np.ndarray] = deque()

    def __call__(self, action: np.ndarray) -> np.ndarray:
        kind, amount, k = self.p.kind, self.p.amount, self.steps
        self.steps += 1
        if kind == "none":
            return action
        if kind == "noise":
            return action + self.joints * self.random.normal(0.0, amount, len(action))
        if kind == "offset":
            if k % OFFSET_PERIOD == 0:
                self.offset = self.joints * self.random.normal(0.0, amount, len(action))
            return action + self.offset
        if kind == "hold":
            if k % int(amount) == 0 or self.held is None:
                self.held = action
            return self.held
        self.queue.append(action)  # delay: the action of `amount` steps ago
        return self.queue.popleft() if len(self.queue) > amount else self.queue[0]
