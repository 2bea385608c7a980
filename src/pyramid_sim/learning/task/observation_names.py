"""The named entries of what a policy observes beyond its own joints, held once for the
environment, a recording and lerobot's plugin. Pure: no MuJoCo."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, NamedTuple

from ...choices import ARMS

BRICK_FIELDS = ("x", "y", "z", "qw", "qx", "qy", "qz")  # a brick's position (m), quaternion
GOAL_FIELDS = ("x", "y", "z", "yaw")  # a target's position (m) and yaw (rad), world frame
TOOL_FIELDS = ("x", "y", "z", "yaw")  # a hand's tool centre (m) and yaw (rad), world frame


class Observed(NamedTuple):
    """What the observation holds beyond the arms' own, carried whole from a task spec to
    the spaces and the names: the bricks' poses (and the goals' fill, judged from them), and
    every goal (else each arm's next alone). A recording's files and a checkpoint's training
    name each the field's way (`OBSERVED`)."""

    brick_poses: bool = True
    all_goals: bool = True

    def hidden(self) -> tuple[str, ...]:
        """The observation's entries left out: the bricks' poses and the goals' fill (judged
        from them), and every goal but the arms' next ones."""
        keys = [] if self.brick_poses else ["bricks", "placed"]
        if not self.all_goals:
            keys += ["goals"] if "placed" in keys else ["goals", "placed"]
        return tuple(keys)

    @property
    def size_free(self) -> bool:
        """Whether the observation's width is the same whatever the structure's size (each
        arm's next goal alone): a policy trained on one size meets another."""
        return not self.all_goals

    @classmethod
    def read(cls, saved: Mapping[str, Any]) -> Observed:
        """What a saved recording's or env's settings (`saved`, by the fields' names) say
        was observed, each field's default where it says nothing (made before the field)."""
        default = cls()
        return cls(*(bool(saved.get(name, getattr(default, name))) for name in cls._fields))


OBSERVED = Observed._fields  # the names of what can be left out of an observation


def environment_names(
    bricks: int, targets: int, brick_poses: bool = True, all_goals: bool = True
) -> tuple[str, ...]:
    """The entries of a recording's `observation.environment_state` and of lerobot's
    `environment_state`: every magazine brick's pose, the pick location's (where the next
    brick is fed: the spot moves from one episode to the next, and a brick's own entries span
    the whole table over an episode, so its few centimetres there are lost in them), every
    target's in build order, whether each holds a brick, each arm's next target (left first),
    each hand's tool pose, left first (as a real arm reports it: its forward kinematics), and
    whether each hand holds a brick (as a real gripper reports it). Without `brick_poses`, no
    brick's pose nor the goals' fill, which is judged from them (a camera policy's input).
    Without `all_goals`, no goal but each arm's next: the same entries whatever the
    structure's size."""
    seen = bricks if brick_poses else 0
    filled = targets if brick_poses and all_goals else 0
    shown = targets if all_goals else 0
    return (
        tuple(f"brick{i}.{f}" for i in range(seen) for f in BRICK_FIELDS)
        + tuple(f"pick.{f}" for f in GOAL_FIELDS)
        + tuple(f"goal{i}.{f}" for i in range(shown) for f in GOAL_FIELDS)
        + tuple(f"goal{i}.placed" for i in range(filled))
        + tuple(f"{arm}_next.{f}" for arm in ARMS for f in GOAL_FIELDS)
        + tuple(f"{arm}_tool.{f}" for arm in ARMS for f in TOOL_FIELDS)
        + tuple(f"{arm}_held" for arm in ARMS)
    )
