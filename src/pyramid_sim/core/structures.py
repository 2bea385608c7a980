"""The catalogue of structures: each generator with its size options, and StructureSpec, a
structure at a size (checked once, where it is made). Pure: no MuJoCo."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..config import BrickConfig
from ..errors import ConfigError
from .brick_manager import MAX_BRICKS, MAX_COURSE, towers, wall, wall_pyramid
from .corner_wall import corner_wall
from .seed_pyramids import (
    MAX_LAYERS,
    SEED_GAPS,
    SEED_START,
    BrickTarget,
    Gaps,
    pyramid,
    pyramid_even,
)

__all__ = [
    "MAX_BRICKS",
    "MAX_COURSE",
    "MAX_LAYERS",
    "SIZE_KNOB",
    "SIZE_OPTIONS",
    "STRUCTURES",
    "BrickTarget",
    "Structure",
    "StructureSpec",
]

Generator = Callable[..., tuple[BrickTarget, ...]]
Resize = Callable[[Any, int], dict[str, int]]  # (a StructureSpec, the knob's value) -> sizes


@dataclass(frozen=True)
class Structure:
    """A structure's one declaration: its generator (None for a goal list, whose targets are
    the goals), its size options with their defaults, and its reach rules: the option `reach`
    grows to find the largest buildable size (`knob`), how the other options follow it
    (`resize`, and `held` says it in words), whether it is laid out from the pick-up spot's y
    whichever arm builds it, and whether it takes the spawn gaps. Every generator takes its
    size options as keywords, then the brick and the spawn spot the layout starts from."""

    generator: Generator | None
    sizes: dict[str, int]
    knob: str | None = None
    resize: Resize | None = None  # default: the knob alone set
    held: Callable[[Any], str] | None = None  # default: the other options as they are
    placed_by_pickup: bool = False
    gaps: bool = True

    def resized(self, spec: Any, value: int) -> dict[str, int]:
        """The size options of `spec` with the knob at `value`."""
        assert self.knob is not None
        return self.resize(spec, value) if self.resize is not None else {self.knob: value}

    def held_fixed(self, spec: Any) -> str:
        """How `resized` holds the other size options while the knob grows (the reach table)."""
        if self.held is not None:
            return self.held(spec)
        others = (f"{k}={v}" for k, v in spec.size.items() if k != self.knob)
        return " ".join(others) or "-"


def _wall_pyramid_size(spec: Any, width: int) -> dict[str, int]:
    """A wall pyramid keeps its layers within its base."""
    return {"width": width, "layers": min(spec.layers or 1, width)}


STRUCTURES: dict[str, Structure] = {
    "pyramid": Structure(pyramid, {"layers": 4}, "layers"),
    "pyramid-even": Structure(pyramid_even, {"layers": 4}, "layers"),
    # the Brick Manager's 15 x 5: both arms only; three full courses (width, width + 1 with
    # the turned ends, width) as it grows
    "wall": Structure(
        wall,
        {"bricks": 13, "width": 4},
        "width",
        lambda spec, width: {"width": width, "bricks": 3 * width + 1},
        lambda spec: "3 courses",
    ),
    "wall-pyramid": Structure(
        wall_pyramid,
        {"width": 5, "layers": 3},
        "width",
        _wall_pyramid_size,
        lambda spec: f"layers=min({spec.layers}, width)",
    ),
    "towers": Structure(towers, {"towers": 4, "layers": 3}, "towers", placed_by_pickup=True),
    # the upstream loop's, the Brick Manager's size: two and a half courses of 6 as it grows
    "corner-wall": Structure(
        corner_wall,
        {"bricks": 15, "width": 5},
        "width",
        lambda spec, width: {"width": width, "bricks": 3 * (width + 1) - (width + 1) // 2},
        lambda spec: "2.5 courses",
        placed_by_pickup=True,
        gaps=False,
    ),
    "list": Structure(None, {}),
}
SIZE_OPTIONS = ("layers", "bricks", "width", "towers")
# Structures laid out from the pick-up spot's y whichever arm builds them.
PLACED_BY_PICKUP = tuple(n for n, s in STRUCTURES.items() if s.placed_by_pickup)
# The option `reach` grows to find the largest buildable size.
SIZE_KNOB = {n: s.knob for n, s in STRUCTURES.items() if s.knob is not None}


@dataclass(frozen=True)
class StructureSpec:
    """A structure and its size: options left None take the structure's defaults; an option
    the structure has no use for is refused (ConfigError), as is a size it cannot have."""

    name: str = "pyramid-even"
    layers: int | None = None
    bricks: int | None = None
    width: int | None = None
    towers: int | None = None
    goals: tuple[BrickTarget, ...] | None = None  # `list`: targets read from a goals file
    goals_source: str = ""  # the goals file, as named in messages and the CSV

    def __post_init__(self) -> None:
        if self.name not in STRUCTURES:
            raise ConfigError(
                f"structure: unknown {self.name!r}; accepted {', '.join(sorted(STRUCTURES))}"
            )
        defaults = STRUCTURES[self.name].sizes
        for option in SIZE_OPTIONS:
            value = getattr(self, option)
            if option in defaults:
                if value is None:
                    object.__setattr__(self, option, defaults[option])
            elif value is not None:
                users = [n for n, d in STRUCTURES.items() if option in d.sizes]
                raise ConfigError(
                    f"{option}: not an option of {self.name}; accepted with {', '.join(users)}"
                )
        if (self.name == "list") != (self.goals is not None):
            raise ConfigError(
                "goals: a goals file is needed by the list structure, and only by it; "
                "accepted --structure list --goals FILE"
            )
        if self.name == "list" and not self.goals:
            raise ConfigError(f"goals: {self.goals_source or 'the file'} holds no goals")
        self.targets(BrickConfig(), SEED_START)  # the generator refuses an impossible size

    @property
    def size(self) -> dict[str, int]:
        """The size options of this structure and their values."""
        if self.name == "list":
            assert self.goals is not None
            return {"goals": len(self.goals)}
        return {o: getattr(self, o) for o in STRUCTURES[self.name].sizes}

    def size_text(self) -> str:
        if self.name == "list":
            return f"goals={self.goals_source}:{self.size['goals']}"
        return " ".join(f"{k}={v}" for k, v in self.size.items())

    def targets(
        self,
        brick: BrickConfig,
        start: tuple[float, float, float],
        pickup_y: float | None = None,
        gaps: Gaps = SEED_GAPS,
    ) -> tuple[BrickTarget, ...]:
        """The resting targets, laid out from `start` (the spawn spot's x and z, the
        structure's centre y) with `gaps` between bricks and beyond the spot (the corner wall
        keeps the Brick Manager's own); goals are absolute and ignore both."""
        declared = STRUCTURES[self.name]
        if declared.generator is None:
            assert self.goals is not None
            return self.goals
        options: dict = {o: getattr(self, o) for o in declared.sizes}
        if declared.placed_by_pickup:
            options["pickup_y"] = start[1] if pickup_y is None else pickup_y
        if declared.gaps:
            options["gaps"] = gaps
        return declared.generator(**options, brick=brick, start=start)
