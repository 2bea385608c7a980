"""A schedule beyond DE NIRO's: the arms pipeline picks and places through two zones, the
spawn spot's and the structure's, as a pure state machine.

DE NIRO's lockstep carries every brick out to the arm's outer clear pose and back, and holds
both arms at a barrier four times a brick over one zone that spans the table. Here each zone is
held by one arm at a time: one arm picks at the spot while the other places at the structure.
An arm that may not enter waits at a standby pose just outside (the dispatch sends it there),
never at the outer clear pose. Two tasks whose arms would reach across each other (`conflict`)
do not run at once. Bricks are picked and placed in build order: the spot goes to the
lowest brick not yet picked, the structure to the lowest not yet placed. A zone is let go once
its holder has finished the task it was given the zone for and the loop sees it outside.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from ..choices import Arm
from .scheduler import Action, Task, other

ZONE_OF = {Action.PICK: "spot", Action.PLACE: "structure"}


class OverlapScheduler:
    """Hands each arm its next pick or place, and each zone to one arm at a time."""

    zones = ("spot", "structure")
    waits_at_standby = True  # an arm refused a zone waits just outside it
    quick_retracts = True  # a retract begins the hand's next turn; a pick's lifts at the free speed

    def __init__(
        self,
        left: Sequence[int],
        right: Sequence[int],
        conflict: Callable[[Task, Task], bool] = lambda a, b: False,
    ) -> None:
        self._conflict = conflict  # whether two arms' tasks may not run at once
        self._queues = {"left": list(left), "right": list(right)}
        self._tasks: dict[str, Task] = {}
        self._holder: dict[str, Task | None] = {z: None for z in self.zones}
        self._inside: dict[str, set[str]] = {z: set() for z in self.zones}
        self._picked: set[int] = set()
        for arm in ("left", "right"):
            self._next(arm)

    @property
    def finished(self) -> bool:
        return all(t.action is Action.IDLE for t in self._tasks.values())

    def task(self, arm: Arm) -> Task:
        return self._tasks[arm]

    def holder(self, zone: str) -> str | None:
        """The arm holding `zone`, if any: what a schedule stepped by hand (or a test) reads."""
        held = self._holder[zone]
        return held.arm if held is not None else None

    def zone_for(self, arm: Arm) -> str:
        """The zone the arm's task needs (for messages)."""
        return ZONE_OF.get(self.task(arm).action, "spot")

    def _next(self, arm: Arm) -> None:
        queue = self._queues[arm]
        if not queue:  # done: out of the way to its clear pose first, then idle
            done_clearing = self._tasks.get(arm, Task(arm, Action.CLEAR)).action is Action.CLEAR
            self._tasks[arm] = Task(arm, Action.IDLE if done_clearing else Action.CLEAR)
        else:
            action = Action.PLACE if queue[0] in self._picked else Action.PICK
            self._tasks[arm] = Task(arm, action, queue[0])

    def _first_waiting(self, zone: str) -> int | None:
        """The brick whose turn it is in `zone`: the lowest not yet picked, or placed."""
        heads = [q[0] for q in self._queues.values() if q]
        if zone == "spot":
            heads = [b for b in heads if b not in self._picked]
        return min(heads) if heads else None

    def may_enter(self, arm: Arm) -> bool:
        """Whether the arm may move into the zone its task needs: its brick's turn there, the
        other arm neither in it nor holding it. Granted, the zone is the arm's until it has
        finished the task and is out."""
        task = self.task(arm)
        zone = ZONE_OF.get(task.action)
        if zone is None:
            return False
        held = self._holder[zone]
        if held is not None:
            return held == task
        if other(arm) in self._inside[zone] or task.brick != self._first_waiting(zone):
            return False
        if any(
            held is not None and held.arm != arm and self._conflict(task, held)
            for held in self._holder.values()
        ):
            return False
        self._holder[zone] = task
        return True

    def report_zone(self, arm: Arm, outside: bool, zone: str) -> None:
        """What the physics loop saw of the arm and `zone`."""
        if not outside:
            self._inside[zone].add(arm)
            return
        self._inside[zone].discard(arm)
        held = self._holder[zone]
        if held is not None and held.arm == arm and held != self.task(arm):
            self._holder[zone] = None

    def complete(self, arm: Arm) -> None:
        """The arm finished its task: a pick is followed by the place of the same brick."""
        task = self.task(arm)
        if task.action is Action.PICK:
            assert task.brick is not None
            self._picked.add(task.brick)
        elif task.action is Action.PLACE:
            self._queues[arm].pop(0)
        self._next(arm)

    def dropped(self, arm: Arm, brick: int) -> None:
        """The arm lost `brick`: it clears, then picks the brick again (it stays first in the
        arm's queue)."""
        self._picked.discard(brick)
        self._tasks[arm] = Task(arm, Action.CLEAR)
