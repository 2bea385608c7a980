"""The action modes by name, as robosuite's controllers are chosen: the one place a mode's
name is looked up. A new mode is a file with its class and a line here."""

from __future__ import annotations

from typing import Protocol

from ...choices import in_words
from ...errors import ConfigError
from ...robots import RobotDescription
from .absolute import AbsoluteMode
from .anchored import AnchoredMode
from .delta import DeltaMode
from .ee import EndEffectorMode
from .joint import JointMode
from .mode import ActionMode, ModeParts
from .relative import RelativeMode
from .unbuilt import check_mode_for_robot
from .waypoint import WaypointMode


class ModeClass(Protocol):
    """A mode's class: made from its parts, and what is known of it before it is made."""

    hand_poses: bool

    def __call__(self, parts: ModeParts) -> ActionMode: ...

    def size(self, robot: RobotDescription) -> int: ...


MODES: dict[str, ModeClass] = {
    "joint": JointMode,
    "relative": RelativeMode,
    "ee": EndEffectorMode,
    "waypoint": WaypointMode,
    "anchored": AnchoredMode,
    "delta": DeltaMode,
    "absolute": AbsoluteMode,
}


def mode_class(name: str) -> ModeClass:
    """The class of the mode `name`; ConfigError naming the modes there are otherwise."""
    if name not in MODES:
        raise ConfigError(f"action mode: unknown {name!r}; accepted {in_words(tuple(MODES))}")
    return MODES[name]


def make_mode(name: str, parts: ModeParts) -> ActionMode:
    """The mode `name`, made from `parts`; ConfigError for a robot its expert does not build
    with (`UNBUILT_MODES`)."""
    check_mode_for_robot(name, parts.config.robot)
    return mode_class(name)(parts)


def action_size(name: str, robot: RobotDescription) -> int:
    """How many entries an action of the mode `name` has for `robot`'s pair (lerobot's
    plugin declares its features with it)."""
    return mode_class(name).size(robot)
