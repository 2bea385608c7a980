"""What a dataset keeps of one frame of an episode, whoever made it (the expert's episode,
the led labels, the filming)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Frame:
    """What a dataset keeps of one frame (one environment step): the observation before the
    action, the action, and the reward, end and success that followed it."""

    state: np.ndarray  # float32, the layout's order
    environment: np.ndarray  # float32: every magazine brick's pose, then every target's
    action: np.ndarray  # float32
    images: dict[str, np.ndarray]  # camera -> H x W x 3 uint8
    reward: float
    done: bool
    success: bool
    primitive: tuple[int, int]  # per arm, left first: an index into episode.PRIMITIVES
    brick: tuple[int, int]  # per arm: the brick (build order) its task handles, -1 for none
