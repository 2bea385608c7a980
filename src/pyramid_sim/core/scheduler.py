"""DE NIRO's four-phase lockstep, as a pure state machine.

Phases, repeated until every brick is placed:
  1. right arm to its outer clear pose, left arm picks;
  2. left arm to its clear pose, right arm picks;
  3. right arm clear, left arm places;
  4. left arm clear, right arm places.
No phase starts before both arms have finished the previous one (DE NIRO's hub barrier), and
within a phase the working arm may enter the shared zone (spawn spot and structure) only after
the clearing arm has reported itself outside it, so the two are never inside together.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import Enum

from ..choices import Arm


class Action(str, Enum):
    PICK = "pick"
    PLACE = "place"
    BUILD = "build"  # pick and place in one go (the overlap schedule)
    CLEAR = "clear"
    IDLE = "idle"


@dataclass(frozen=True)
class Task:
    """What one arm does in one phase; `brick` is the build-order index for pick and place."""

    arm: Arm
    action: Action
    brick: int | None = None


# (working arm, its action) per phase; the other arm clears.
PHASES: tuple[tuple[Arm, Action], ...] = (
    ("left", Action.PICK),
    ("right", Action.PICK),
    ("left", Action.PLACE),
    ("right", Action.PLACE),
)


def other(arm: Arm) -> Arm:
    return "right" if arm == "left" else "left"


class LockstepScheduler:
    """Hands each arm its task for the current phase and advances at the barrier."""

    zones = ("shared",)
    waits_at_standby = False  # an arm waits at its outer clear pose, as DE NIRO's does
    quick_retracts = False  # DE NIRO's slow retracts, each move turning the hand on its own

    def __init__(self, left: Sequence[int], right: Sequence[int]) -> None:
        self._queues = {"left": list(left), "right": list(right)}
        self._holding: dict[str, int | None] = {"left": None, "right": None}
        self._phase = -1
        self._tasks: dict[str, Task] = {}
        self._done: set[str] = set()
        self._outside: set[str] = set()
        self._advance()

    @property
    def phase(self) -> int:
        """Current phase, 1 to 4 as in DE NIRO's (0 once finished): where a schedule stepped by
        hand (or a test) stands."""
        return 0 if self.finished else self._phase + 1

    @property
    def finished(self) -> bool:
        return not self._tasks

    def task(self, arm: Arm) -> Task:
        """The arm's task in the current phase (IDLE when it has none)."""
        return self._tasks.get(arm, Task(arm, Action.IDLE))

    def may_enter(self, arm: Arm) -> bool:
        """Whether the arm may move into the shared zone now."""
        if self.finished:
            return False
        if self.task(arm).action not in (Action.PICK, Action.PLACE):
            return False
        return other(arm) in self._outside

    def zone_for(self, arm: Arm) -> str:
        """The zone the arm's task needs (for messages): there is one."""
        return "shared"

    def report_zone(self, arm: Arm, outside: bool, zone: str = "shared") -> None:
        """What the physics loop saw: is every tracked point of `arm` outside the shared zone?"""
        if outside:
            self._outside.add(arm)
        else:
            self._outside.discard(arm)

    def complete(self, arm: Arm) -> None:
        """The arm finished its task; once both have, the next phase starts."""
        task = self.task(arm)
        if task.action is Action.PICK:
            self._holding[arm] = task.brick
        elif task.action is Action.PLACE:
            self._holding[arm] = None
        self._done.add(arm)
        if self._done >= set(self._tasks):
            self._advance()

    def dropped(self, arm: Arm, brick: int) -> None:
        """The arm lost `brick` between grip and release: the brick goes back to the front of
        the arm's queue (its next pick fetches a new one) and the arm's task in this phase
        becomes a clear, so the phase still ends at the barrier."""
        self._holding[arm] = None
        self._queues[arm].insert(0, brick)
        if arm in self._tasks:
            self._tasks[arm] = Task(arm, Action.CLEAR)

    def _advance(self) -> None:
        """Move to the next phase that has work, skipping phases whose working arm has none."""
        for _ in range(len(PHASES)):
            self._phase = (self._phase + 1) % len(PHASES)
            worker, action = PHASES[self._phase]
            brick = self._next_brick(worker, action)
            if brick is None:
                continue
            self._tasks = {
                worker: Task(worker, action, brick),
                other(worker): Task(other(worker), Action.CLEAR),
            }
            self._done = set()
            return
        self._tasks = {}

    def _next_brick(self, arm: Arm, action: Action) -> int | None:
        if action is Action.PICK:
            if self._holding[arm] is not None or not self._queues[arm]:
                return None
            return self._queues[arm].pop(0)
        return self._holding[arm]
