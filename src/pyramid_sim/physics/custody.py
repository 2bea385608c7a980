"""Brick custody: which brick is in which hand, how far it slipped, which were dropped or
knocked off, and which brick the spawn spot gets next (a dropped one lying on the spot, else the
next from the magazine)."""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from ..choices import Arm
from ..config import DROP_DISTANCE, SimConfig
from ..core.incidents import (
    MAX_DROPS_PER_BRICK,
    Drop,
    Knock,
    KnockWatch,
    grip_diagnosis,
)
from ..core.primitives import Step, StepKind
from . import names as c
from .handles import SceneHandles
from .hold_sense import HoldSense
from .spawner import Spawner


@dataclass
class Carry:
    """A brick in a hand: its slot, build index and pose in the tool frame at the grip."""

    slot: int
    index: int
    offset: np.ndarray
    max_slip: float = 0.0


class BrickCustody:
    """Every brick's whereabouts during a build, from the spawn spot to its place."""

    def __init__(
        self,
        data: mujoco.MjData,
        handles: SceneHandles,
        spawner: Spawner,
        bricks: int,
        config: SimConfig,
    ) -> None:
        self.data, self.handles, self.spawner = data, handles, spawner
        self.bricks = bricks  # in the structure
        self.config = config
        self.carry: dict[str, Carry | None] = {a: None for a in c.ARMS}
        self.slot_of: dict[int, int] = {}  # build-order index -> slot of the brick placed there
        self.slip_mm: dict[int, float] = {}
        self.drops: list[Drop] = []
        self.lost: list[int] = []  # slots of dropped bricks, not (yet) picked again
        self.knocks: list[Knock] = []
        self.knock_watch = KnockWatch()
        self._awake_before = False
        self._body_awake = data.body_awake  # a view MuJoCo keeps up
        self.failure: str | None = None  # set when a brick has been dropped too often
        self.holds = HoldSense(data.model, handles, config.robot_description)
        self.lifted: set[int] = set()  # slots a hand took off the spot
        # Where each brick lay when it was last put down by the magazine or the spawner, and
        # the bricks no arm has reached for yet: how far those move is `idle_motion`.
        self.rest = np.array([data.qpos[q : q + 3] for q in handles.brick_qpos])
        self.untouched = set(range(handles.n_bricks))
        self.idle_motion = 0.0  # m, the furthest a brick moved before an arm reached for it

    def tcp(self, arm: Arm) -> tuple[np.ndarray, np.ndarray]:
        site = self.handles.tcp_site[arm]
        return self.data.site_xpos[site], self.data.site_xmat[site].reshape(3, 3)

    def brick_in_tcp(self, arm: Arm, slot: int) -> np.ndarray:
        p, r = self.tcp(arm)
        return r.T @ (self.data.xpos[self.handles.brick_body[slot]] - p)

    def _note_idle(self, slot: int) -> None:
        q = self.handles.brick_qpos[slot]
        moved = float(np.linalg.norm(self.data.qpos[q : q + 3] - self.rest[slot]))
        self.idle_motion = max(self.idle_motion, moved)

    def reached(self, slot: int) -> None:
        """An arm's fingers are around the brick in `slot`: from now on it is handled."""
        if slot in self.untouched:
            self._note_idle(slot)
            self.untouched.discard(slot)

    def finish(self) -> None:
        """At the end of a build: how far the bricks nobody reached for have moved."""
        for slot in self.untouched:
            self._note_idle(slot)

    def notice_taken(self) -> None:
        """The brick offered on the spot no longer lies there: whoever took it (or knocked it
        off), the spot is free for the next."""
        slot = self.spawner.current
        if slot is not None and not self.spawner.rests_on_spot(self.data, slot, now=True):
            self.reached(slot)
            self.spawner.taken(slot)
            if any(slot in held for held in self.holds.slots(self.data)):
                self.lifted.add(slot)  # a hand took it, whoever drives the arms

    def picked(self) -> int:
        """How many bricks hands have taken off the spot for the structure: the scripted
        builder's grips (a drop takes one back), and bricks that left the spot in a hand no
        grip was counted for (a learner drives the arms: no builder's grip to count)."""
        return len(self.slot_of) + len(self.lifted - set(self.slot_of.values()))

    def gripped(self, arm: Arm, brick: int) -> None:
        """The arm closed on the brick for build-order place `brick`: the one last offered on
        the spot, or, taken up again to be set right, the one let go there."""
        if brick in self.knock_watch.bricks:  # a re-place: no longer watched where it lay
            slot = self.slot_of[brick]
            self.knock_watch.forget(slot)
        else:
            offered = self.spawner.offered
            assert offered is not None
            slot = offered
            self.spawner.taken(slot)
            self.slot_of[brick] = slot
        self.carry[arm] = Carry(slot, brick, self.brick_in_tcp(arm, slot).copy())

    def placed(self) -> int:
        """How many bricks have been let go at their places (each counted once)."""
        return len(self.knock_watch.bricks)

    def released(self, brick: int) -> None:
        """The brick for place `brick` was let go: from now on it is watched for knocks."""
        slot = self.slot_of[brick]
        body = self.handles.brick_body[slot]
        self.knock_watch.placed(brick, slot, body, self.data.xpos[body].copy())

    def track(self, steps: dict[str, Step | None]) -> list[Drop]:
        """Once per control step, given each arm's current step: the slip of each carried
        brick, and the bricks that left a hand (a drop). The third drop of one brick sets
        `failure`, saying why."""
        dropped = []
        for arm in c.ARMS:
            carry = self.carry[arm]
            if carry is None:
                continue
            step = steps[arm]
            if step is not None and step.kind is StepKind.RELEASE:
                # Set down: the carry is over, what follows is the release.
                self.slip_mm[carry.index] = carry.max_slip * 1000.0
                self.carry[arm] = None
                continue
            slip = float(np.linalg.norm(self.brick_in_tcp(arm, carry.slot) - carry.offset))
            carry.max_slip = max(carry.max_slip, slip)
            if slip > DROP_DISTANCE:
                drop = self._drop(arm, carry, step.name if step is not None else "idle")
                if self.failure is None:
                    dropped.append(drop)
        return dropped

    def _drop(self, arm: Arm, carry: Carry, step: str) -> Drop:
        """Record a brick that left the hand. One that comes to rest on the spawn spot is
        picked again; one that lands elsewhere is replaced by a spare (`feed_spot`)."""
        d = self.data
        on_spot = self.spawner.rests_on_spot(d, carry.slot)
        x, y, z = (float(v) for v in d.xpos[self.handles.brick_body[carry.slot]])
        drop = Drop(carry.index, arm, carry.slot, float(d.time), (x, y, z), step, on_spot)
        self.drops.append(drop)
        self.carry[arm] = None
        self.slot_of.pop(carry.index, None)
        self.lifted.discard(carry.slot)
        if sum(e.brick == carry.index for e in self.drops) >= MAX_DROPS_PER_BRICK:
            self.failure = (
                f"brick {carry.index} dropped {MAX_DROPS_PER_BRICK} times; last, "
                f"{drop.describe()}: {grip_diagnosis(self.config)}"
            )
        else:
            self.lost.append(carry.slot)  # picked again if it comes to rest on the spot
        return drop

    def check_knocks(self) -> None:
        """Placed bricks that moved away from where they were let go. A brick MuJoCo has put
        to sleep cannot move, so the positions are compared only while a placed brick is awake,
        or was at the last look (it may have moved in between, then fallen asleep)."""
        awake = bool(self._body_awake[self.knock_watch.bodies].any())
        if awake or self._awake_before:
            self.knocks.extend(self.knock_watch.check(self.data.xpos, float(self.data.time)))
        self._awake_before = awake

    def needs_brick(self) -> bool:
        """A brick is needed while some pick is still to come."""
        return self.picked() + (1 if self.spawner.current is not None else 0) < self.bricks

    def feed_spot(self) -> int | None:
        """Give the next pick a brick: a dropped one lying on the spot as spawned is picked
        again, else the next from the magazine once the spot and the hands are clear. Returns
        the slot of a newly spawned brick."""
        d = self.data
        back = next((s for s in self.lost if self.spawner.rests_on_spot(d, s)), None)
        if back is not None:
            self.lost.remove(back)
            self.spawner.put_back(back)
        elif self.spawner.remaining > 0 and self.spawner.spot_clear(d):
            slot = self.spawner.next_slot
            self._note_idle(slot)  # parked until now
            self.spawner.spawn_next(d)
            q = self.handles.brick_qpos[slot]
            self.rest[slot] = d.qpos[q : q + 3]
            return slot
        else:
            self._check_spot_blocked()
        return None

    def _check_spot_blocked(self) -> None:
        """A dropped brick at rest in the spot's way, but not lying as spawned, can neither be
        picked again nor let the next brick onto the spot: the build cannot go on (rather than
        stall until `stall_time`). At rest is asleep: MuJoCo wakes a brick anything touches."""
        d = self.data
        for slot in self.lost:
            body = self.handles.brick_body[slot]
            if d.body_awake[body] or not self.spawner.in_the_way(d, slot):
                continue
            drop = next(e for e in reversed(self.drops) if e.slot == slot)
            self.failure = (
                f"{drop.describe()}; it came to rest in the spawn spot's way, "
                f"{self.spawner.off_spot(d, slot)}: too far to be picked again, and no brick can be "
                f"set on the spot past it: {grip_diagnosis(self.config)}"
            )
            return
