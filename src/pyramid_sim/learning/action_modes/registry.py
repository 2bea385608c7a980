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


# The modes a robot's expert has not been shown to build in, refused for it up front: each
# robot's expert builds at `layout` in every other mode (tests/physics/test_holding_torque.py)
UNBUILT_MODES = {
    "so101": {
        "delta": "its expert ran to the time limit on seeds 100000-100001",
        "absolute": "delta's bound and controller, with which its expert ran to the time limit",
    },
    "baxter": {
        "delta": "its expert braked past a joint's torque limit on seeds 100000-100001",
        "absolute": "delta's bound and controller, with which its expert braked past a torque",
    },
}


def check_mode_for_robot(name: str, robot: str, offered: tuple[str, ...] = ()) -> None:
    """ConfigError for a mode whose expert does not build with `robot` (UNBUILT_MODES),
    naming those of `offered` (default every mode: `record` offers fewer) it builds in."""
    unbuilt = UNBUILT_MODES.get(robot, {})
    if name in unbuilt:
        accepted = in_words(tuple(m for m in offered or tuple(MODES) if m not in unbuilt))
        raise ConfigError(
            f"action mode: {name!r} is not offered for {robot} ({unbuilt[name]}); "
            f"accepted {accepted}"
        )


def make_mode(name: str, parts: ModeParts) -> ActionMode:
    """The mode `name`, made from `parts`; ConfigError for a robot its expert does not build
    with (`UNBUILT_MODES`)."""
    check_mode_for_robot(name, parts.config.robot)
    return mode_class(name)(parts)


def action_size(name: str, robot: RobotDescription) -> int:
    """How many entries an action of the mode `name` has for `robot`'s pair (lerobot's
    plugin declares its features with it)."""
    return mode_class(name).size(robot)
