"""The catalogue of structures: each generator with its size options, and StructureSpec, a
structure at a size (checked once, where it is made). Pure: no MuJoCo."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

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
    "StructureSpec",
]

# name -> (generator, its size options with their defaults). Every generator takes its size
# options as keywords, then the brick and the spawn spot the layout starts from; a goal list
# has no generator (its targets are the goals).
STRUCTURES: dict[str, tuple[Callable[..., tuple[BrickTarget, ...]] | None, dict[str, int]]] = {
    "pyramid": (pyramid, {"layers": 4}),
    "pyramid-even": (pyramid_even, {"layers": 4}),
    "wall": (wall, {"bricks": 13, "width": 4}),  # the Brick Manager's 15 x 5: both arms only
    "wall-pyramid": (wall_pyramid, {"width": 5, "layers": 3}),
    "towers": (towers, {"towers": 4, "layers": 3}),
    "corner-wall": (
        corner_wall,
        {"bricks": 15, "width": 5},
    ),  # the upstream loop's, the Brick Manager's size
    "list": (None, {}),
}
SIZE_OPTIONS = ("layers", "bricks", "width", "towers")
# Structures laid out from the pick-up spot's y whichever arm builds them.
PLACED_BY_PICKUP = ("towers", "corner-wall")
# The option `reach` grows to find the largest buildable size.
SIZE_KNOB = {
    "pyramid": "layers",
    "pyramid-even": "layers",
    "wall": "width",
    "wall-pyramid": "width",
    "towers": "towers",
    "corner-wall": "width",
}


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
        defaults = STRUCTURES[self.name][1]
        for option in SIZE_OPTIONS:
            value = getattr(self, option)
            if option in defaults:
                if value is None:
                    object.__setattr__(self, option, defaults[option])
            elif value is not None:
                users = [n for n, (_, d) in STRUCTURES.items() if option in d]
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
        return {o: getattr(self, o) for o in STRUCTURES[self.name][1]}

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
        generator, defaults = STRUCTURES[self.name]
        if generator is None:
            assert self.goals is not None
            return self.goals
        options: dict = {o: getattr(self, o) for o in defaults}
        if self.name in PLACED_BY_PICKUP:
            options["pickup_y"] = start[1] if pickup_y is None else pickup_y
        if self.name != "corner-wall":
            options["gaps"] = gaps
        return generator(**options, brick=brick, start=start)
