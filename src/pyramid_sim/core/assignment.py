"""Which arm places which brick, and in what order: DE NIRO's `arrange_coordinates`."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

from ..choices import Arm
from .structures import BrickTarget


@dataclass(frozen=True)
class Assignment:
    """One brick of the build order: its index in that order, its arm and its target."""

    index: int
    arm: Arm
    target: BrickTarget


# the left arm takes the largest y of a layer, the right the smallest
ARM_PICKS: tuple[tuple[Arm, Callable[..., BrickTarget]], ...] = (("left", max), ("right", min))


def arrange(targets: Sequence[BrickTarget]) -> tuple[Assignment, ...]:
    """Lowest layer first; the left arm takes the remaining brick of that layer with the largest
    y, then the right arm the one with the smallest y, alternating; with an odd count the left
    arm places the last brick. (DE NIRO compares z values; layers are compared here, which is
    the same for its structures and is exact.)"""
    remaining = list(targets)
    order: list[Assignment] = []
    while remaining:
        for arm, pick in ARM_PICKS:
            if not remaining:
                break
            lowest = min(t.layer for t in remaining)
            layer = [t for t in remaining if t.layer == lowest]
            chosen = pick(layer, key=lambda t: t.pose.y)
            remaining.remove(chosen)
            order.append(Assignment(len(order), arm, chosen))
    return tuple(order)


def single_arm(targets: Sequence[BrickTarget], arm: Arm) -> tuple[Assignment, ...]:
    """Every brick to one arm, in the structure's own order, lowest course first (a goal list's
    order is kept within each course: the generators and a sensible list are bottom-up)."""
    ordered = sorted(targets, key=lambda t: t.layer)  # stable: keeps the order within a course
    return tuple(Assignment(i, arm, t) for i, t in enumerate(ordered))
