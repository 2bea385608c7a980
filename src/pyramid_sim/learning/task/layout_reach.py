"""How large a structure the arms build wherever the `layout` variation puts it: every pose
checked by IK at the corners of the layout's region (the structure shifted and turned to each
extreme with the spawn spot at DE NIRO's, and the spawn spot at each extreme with the
structure at DE NIRO's place). A draw inside the region whose pose is still out of reach is
drawn again (learning/task/variation.py)."""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from typing import Any

from ...choices import ArmChoice
from ...config import SimConfig
from ...core.plan import make_plan
from ...core.structures import SIZE_KNOB, StructureSpec
from ...errors import ConfigError, UnreachableError
from ...physics.reach import ReachChecker, resized
from . import variation as var


def corner_draws() -> Iterator[dict[str, Any]]:
    """The 16 layouts at the region's corners, as `variation.draw_layout` gives a draw."""
    s, t = var.STRUCTURE_SHIFT, var.STRUCTURE_TURN
    for sx, sy, turn in itertools.product((-s, s), (-s, s), (-t, t)):
        yield {
            "spawn_offset": [0.0, 0.0],
            "spawn_turn": 0.0,
            "structure_shift": [sx, sy],
            "structure_turn": turn,
        }
    x, y = var.SPAWN_REGION
    for dx, dy, turn in itertools.product((-x, x), (-y, y), (-var.SPAWN_TURN, 0.0)):
        yield {
            "spawn_offset": [dx, dy],
            "spawn_turn": turn,
            "structure_shift": [0.0, 0.0],
            "structure_turn": 0.0,
        }


def reaches_every_corner(
    checker: ReachChecker, spec: StructureSpec, config: SimConfig, arms: ArmChoice
) -> bool:
    """Whether every pose of `spec` is within reach at each corner of the layout's region."""
    try:
        for drawn in corner_draws():
            checker.check(make_plan(spec, var.placed(config, drawn), arms))
    except UnreachableError:
        return False
    return True


def largest_in_every_layout(
    checker: ReachChecker, spec: StructureSpec, arms: ArmChoice, below: int
) -> int:
    """The largest size knob value under `below` (the largest reachable where DE NIRO put
    things, plus one) reachable at every corner of the layout's region; 0 for none."""
    for value in range(below - 1, 0, -1):
        try:
            sized = resized(spec, SIZE_KNOB[spec.name], value)
        except ConfigError:
            continue
        if reaches_every_corner(checker, sized, checker.config, arms):
            return value
    return 0
