"""A schedule beyond the seed's: each arm carries a brick straight from the spawn spot to its
place, and the arms take turns in the shared zone, as a pure state machine.

The seed's lockstep carries every brick out to the arm's outer clear pose and back, and holds
both arms at a barrier four times a brick. Here an arm holding the zone picks and places in one
go (BUILD), then leaves (CLEAR); the other arm, already on its way, enters the moment the first
is out. Bricks are still placed in build order: an arm takes the zone only for the lowest brick
not yet placed. The two arms are never in the zone together.
"""

from __future__ import annotations

from typing import Sequence

from .scheduler import Action, Task, other


class OverlapScheduler:
    """Hands each arm its task and the zone, one arm at a time, in build order."""

    def __init__(self, left: Sequence[int], right: Sequence[int]) -> None:
        self._queues = {"left": list(left), "right": list(right)}
        self._tasks: dict[str, Task] = {}
        self._holder: str | None = None  # the arm building in the zone, until it is out again
        self._outside: set[str] = set()
        self._placed: set[int] = set()
        for arm in ("left", "right"):
            self._next(arm)

    @property
    def finished(self) -> bool:
        return all(t.action is Action.IDLE for t in self._tasks.values())

    def task(self, arm: str) -> Task:
        return self._tasks[arm]

    def _next(self, arm: str) -> None:
        queue = self._queues[arm]
        self._tasks[arm] = Task(arm, Action.BUILD, queue[0]) if queue else Task(arm, Action.IDLE)

    def _lowest_unplaced(self) -> int | None:
        waiting = [q[0] for q in self._queues.values() if q]
        return min(waiting) if waiting else None

    def may_enter(self, arm: str) -> bool:
        """Whether the arm may move into the zone now: for the lowest brick not yet placed,
        with the other arm out of the zone and not holding it."""
        task = self.task(arm)
        if task.action is not Action.BUILD:
            return False
        if self._holder == arm:
            return True
        if self._holder is not None or other(arm) not in self._outside:
            return False
        if task.brick != self._lowest_unplaced():
            return False
        self._holder = arm
        return True

    def report_zone(self, arm: str, outside: bool) -> None:
        """What the physics loop saw; an arm that left the zone after its task lets go of it."""
        if outside:
            self._outside.add(arm)
            if self._holder == arm and self.task(arm).action is not Action.BUILD:
                self._holder = None
        else:
            self._outside.discard(arm)

    def complete(self, arm: str) -> None:
        """The arm finished its task: after a BUILD it leaves the zone, after that its next."""
        task = self.task(arm)
        if task.action is Action.BUILD:
            assert task.brick is not None
            self._queues[arm].pop(0)
            self._placed.add(task.brick)
            self._tasks[arm] = Task(arm, Action.CLEAR)
        else:  # out at its clear pose: the zone is free whatever the loop saw last
            if self._holder == arm:
                self._holder = None
            self._next(arm)

    def dropped(self, arm: str, brick: int) -> None:
        """The arm lost `brick`: it leaves the zone, and builds the brick again next (the
        brick never left its queue)."""
        self._tasks[arm] = Task(arm, Action.CLEAR)
