"""What an action mode is: one class per mode behind one protocol, as robosuite's controllers
are (ManiSkill's `control_mode` names one). A mode owns its action space, entries and their
units; the target an action sets at a step's start and the command that heads for it each
control step; the expert's label in its form; what holding still is; and its reset. The
environment, the expert, a recording and the perturbations ask the mode (registry.py finds
one by name); none of them asks which mode it is."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
from gymnasium import spaces

from ...config import SimConfig
from ...physics.loop import BuildLoop
from ...robots import RobotDescription
from ..task.layout import Layout
from ..task.lerobot_units import LerobotUnits

# An action as the waypoint it asks for, and what gives a waypoint back in the mode's form.
Waypoints = tuple[np.ndarray, Callable[[np.ndarray], np.ndarray]]


@dataclass(frozen=True)
class ModeParts:
    """What a mode is made from: the settings, the state's layout, the control steps an
    environment step lasts, the joint command's lerobot units, and whether the motion
    generator stands between the command and the servos (`limit_commands`)."""

    config: SimConfig
    layout: Layout
    steps: int
    units: LerobotUnits
    limit_commands: bool


@dataclass(frozen=True)
class ExpertMove:
    """What the scripted builder did over one environment step, for a mode to label: its
    last joint command (where the builder's own IK solved it, else None), whether it still
    moves, and the state measured at the step."""

    loop: BuildLoop
    joints: np.ndarray | None
    moving: bool
    state: np.ndarray


class ActionMode(Protocol):
    """One way a policy's action moves the arms."""

    space: spaces.Box  # the action space
    names: tuple[str, ...]  # its entries, as an action's check names them
    units: LerobotUnits  # its entries as lerobot records them: names and units
    moved: np.ndarray  # bool, per entry: it moves an arm (DART's noise, the perturbations)
    moved_unit: str  # of the entries that move an arm: "rad" or "m"
    jerk_time: float  # s from rest to full acceleration: the motion generator's jerk limit
    acceleration_share: float  # of the joints' acceleration limits the generator uses
    hand_poses: bool  # its actions are hand poses its own IK follows (the expert gives poses)

    @classmethod
    def size(cls, robot: RobotDescription) -> int:
        """How many entries an action of `robot`'s pair has."""
        ...

    def reset(self, loop: BuildLoop) -> None:
        """A new episode's build, its arms where they stand."""

    def see(self, observation: dict[str, Any]) -> None:
        """What the policy observed: the frames of its next action, where a mode has any."""

    def target(self, action: np.ndarray, state: np.ndarray) -> np.ndarray:
        """What a checked action asks of the arms, at the step's start (`state` measured)."""
        ...

    def command(self, loop: BuildLoop, target: np.ndarray, share: float) -> np.ndarray:
        """The joint command for the control step `share` through the environment step, on
        the way to `target` (before any motion generator)."""
        ...

    def held(self, loop: BuildLoop, state: np.ndarray) -> np.ndarray:
        """The action that keeps both arms and hands as commanded now (float32)."""
        ...

    def expert(self, move: ExpertMove) -> np.ndarray:
        """The scripted builder's `move` as an action of this mode (float32)."""
        ...

    def waypoints(self, action: np.ndarray) -> Waypoints | None:
        """`action` as the waypoint it asks for, and what gives a waypoint back in this mode's
        form (a recording's led labels); None where its actions are no waypoints."""
        ...
