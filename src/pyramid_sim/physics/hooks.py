"""The one door into a running build: progress, rendering, fault injection and recording.

Every hook is optional and none is called when unset, so a build without hooks runs the bare
loop. Hooks get the physics state, not the loop. Only `on_step` may change the state (tests use
it to knock bricks about); the others read.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import mujoco


@dataclass(frozen=True)
class BuildHooks:
    on_placed: Callable[[int], Any] | None = None  # bricks placed so far, after each release
    on_frame: Callable[[mujoco.MjModel, mujoco.MjData], Any] | None = None  # every frame_dt
    frame_dt: float | None = None  # simulated seconds between frames
    on_step: Callable[[mujoco.MjData], Any] | None = None  # after every physics step
    on_spawn: Callable[[int, mujoco.MjData], Any] | None = None  # a brick set on the spot
    on_ik: Callable[[float], Any] | None = None  # wall seconds of each IK solve (timed only then)
