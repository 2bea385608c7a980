"""How much one episode differs from the next: named levels, the same in the environment,
`record` and evaluation. Each episode's draw comes from its seed alone.

- `fixed`: DE NIRO's layout (its spawn spot, the structure where its generator lays it);
  only the physics' own determinism and any spawn jitter set.
- `layout`: where the bricks are fed (the spawn spot anywhere in `SPAWN_REGION`, its yaw turned by up
  to `SPAWN_TURN`), where the structure stands and which way it faces (shifted within
  `STRUCTURE_SHIFT`, turned within `STRUCTURE_TURN`). The expert plans for each draw.
- `full`: the layout and every part of `randomize` (physical and visual).

The zero draw (every offset 0) is the `fixed` layout.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from ...choices import DEFAULT_VARIATION, VARIATIONS
from ...config import SimConfig
from ...errors import ConfigError
from .randomize import PARTS

LEVELS, DEFAULT_LEVEL = VARIATIONS, DEFAULT_VARIATION
STREAM = 0x1A70  # the layout's own random stream beside the episode seed's others
SPAWN_REGION = (0.03, 0.04)  # m either side of DE NIRO's spawn spot, in x and y
# The spawn yaw turned clockwise by up to this: DE NIRO's quarter turn is where the grasp's
# two yaws tie, and a brick turned the other way is gripped the other way round, out of the
# right arm's wrist range.
SPAWN_TURN = math.radians(20.0)
STRUCTURE_SHIFT = 0.05  # m either way in x and y
STRUCTURE_TURN = math.radians(15.0)  # either way, about the footprint's centre
# m beyond the feeder's clearance a drawn structure keeps from the spot: an open hand picking
# there is wider than the brick (at 1 cm a Panda's fingers struck the structure, 1 in 100)
SPOT_MARGIN = 0.04
ATTEMPTS = 20  # draws of a layout before a structure is refused as out of reach


def check_level(level: str) -> str:
    """The level, if it is one of LEVELS: ConfigError naming those otherwise."""
    if level not in LEVELS:
        raise ConfigError(f"variation: unknown {level!r}; accepted {', '.join(LEVELS)}")
    return level


def randomized(level: str, parts: tuple[str, ...]) -> tuple[str, ...]:
    """The randomization parts an episode draws: every one at `full`, else those asked."""
    return PARTS if level == "full" else parts


def draw_layout(seed: int, level: str, attempt: int = 0) -> dict[str, Any]:
    """The layout of the episode of `seed` at `level` (empty at `fixed`): plain numbers, as
    the episode's record keeps them. A draw that puts a pose out of the arms' reach, the
    structure where the feeder sets no brick, or a brick where its arm could barely hold it
    still, is drawn again (`attempt` 1, 2, ...: the environment tries up to ATTEMPTS), so the
    region a structure is drawn in is the part of the ranges its every pose reaches."""
    if level == "fixed":
        return {}
    rng = np.random.default_rng([seed, STREAM, attempt] if attempt else [seed, STREAM])
    dx, dy = (float(v) for v in rng.uniform(-1.0, 1.0, 2) * SPAWN_REGION)
    return {
        "attempt": attempt,
        "spawn_offset": [dx, dy],
        "spawn_turn": float(rng.uniform(-SPAWN_TURN, 0.0)),
        "structure_shift": [float(v) for v in rng.uniform(-STRUCTURE_SHIFT, STRUCTURE_SHIFT, 2)],
        "structure_turn": float(rng.uniform(-STRUCTURE_TURN, STRUCTURE_TURN)),
    }


def placed(config: SimConfig, drawn: dict[str, Any]) -> SimConfig:
    """The settings with a drawn layout applied (the settings themselves for an empty one),
    its lengths scaled to the robot's (`length_scale`)."""
    if not drawn:
        return config
    layout = config.layout  # the draw is an offset from the settings' own layout
    k = config.robot_description.length_scale  # the draw's lengths are at DE NIRO's scale
    x, y = layout.spawn_xy
    dx, dy = drawn["spawn_offset"]
    sx, sy = layout.structure_shift
    shift = drawn["structure_shift"]
    return replace(
        config,
        layout=replace(
            layout,
            spawn_xy=(x + k * dx, y + k * dy),
            spawn_yaw=layout.spawn_yaw + drawn["spawn_turn"],
            structure_shift=(sx + k * shift[0], sy + k * shift[1]),
            structure_turn=layout.structure_turn + drawn["structure_turn"],
        ),
    )


def check_differ(episodes: int, level: str, parts: tuple[str, ...], jitter_mm: float) -> None:
    """ConfigError for a recording whose episodes would all be the same: more than one at the
    `fixed` level with nothing drawn from the seed (no randomization, no spawn jitter)."""
    if episodes > 1 and level == "fixed" and not parts and jitter_mm == 0.0:
        raise ConfigError(
            f"episodes: {episodes} episodes at variation fixed, with no randomization and no "
            "spawn jitter, would all be the same; accepted 1 episode there, or variation "
            "layout or full"
        )
