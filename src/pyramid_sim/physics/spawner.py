"""The brick spawner: a magazine of parked bricks, the next one set on the spawn spot when the
previous one has been taken away (MuJoCo cannot add bodies without recompiling)."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from ..core.poses import Pose, symmetric_yaw_error, tilt_of, yaw_of, yaw_quaternion
from ..robots import RobotDescription
from . import names as c
from .clearance import arm_geoms
from .handles import SceneHandles

ON_SPOT_XY = 0.004  # m beyond the spawn jitter: still picked at the nominal spot
ON_SPOT_Z = 0.003  # m
ON_SPOT_ANGLE = math.radians(3.0)  # tilt and turn


class Spawner:
    """Sets bricks on the spawn spot one at a time, each up to `jitter` off it in x and y (drawn
    from `seed`), as an imprecise feeder would: the arms still pick at the nominal spot."""

    def __init__(
        self,
        model: mujoco.MjModel,
        robot: RobotDescription,
        handles: SceneHandles,
        spawn: Pose,
        clearance: float,
        arm_clearance: float,
        jitter: float = 0.0,
        seed: int = 0,
    ) -> None:
        self.model, self.spawn = model, spawn
        self.clearance, self.arm_clearance = clearance, arm_clearance
        self.volume = model.geom(c.SPAWN_VOLUME).id
        self.arm_geoms = [g for a in c.ARMS for g in arm_geoms(model, robot.arms[a])]
        self._fromto = np.zeros(6)
        self._rot = np.zeros(9)
        self.jitter = jitter
        self.rng = np.random.default_rng(seed)
        self.handles = handles
        self.body = handles.brick_body
        self.next_slot = 0
        self.current: int | None = None  # slot on the spawn spot, not yet taken
        self.offered: int | None = None  # slot last set on the spot (taken or not)

    @property
    def remaining(self) -> int:
        return self.handles.n_bricks - self.next_slot

    def brick_ready(self) -> bool:
        return self.current is not None

    def taken(self, slot: int) -> None:
        """An arm gripped the brick in `slot`: the spot is no longer holding a fresh brick."""
        if slot == self.current:
            self.current = None

    def spot_clear(self, data: mujoco.MjData) -> bool:
        """Whether no brick set out so far is within `clearance` of the spawn volume (the
        brick's box at the spot, grown by the jitter), and no link of either arm within
        `arm_clearance` (a feeder does not push a brick under a moving hand). Exact shapes
        (mj_geomDistance) behind a bounding-sphere filter."""
        bricks = [self.model.body_geomadr[b] for b in self.body[: self.next_slot]]
        return self._apart(data, bricks, self.clearance) and self._apart(
            data, self.arm_geoms, self.arm_clearance
        )

    def _apart(self, data: mujoco.MjData, geoms: list, clearance: float) -> bool:
        m, vol = self.model, self.volume
        centre, reach = data.geom_xpos[vol], m.geom_rbound[vol] + clearance
        for g in geoms:
            if np.linalg.norm(data.geom_xpos[g] - centre) - m.geom_rbound[g] > reach:
                continue
            if mujoco.mj_geomDistance(m, data, vol, int(g), clearance, self._fromto) < clearance:
                return False
        return True

    def spot_offset(
        self, data: mujoco.MjData, slot: int, now: bool = False
    ) -> tuple[float, float, float, float]:
        """How far the brick in `slot` lies from the spot as spawned: across (m), up or down
        (m), its tilt and its turn (rad). As of the last physics step's kinematics, or `now`
        from its joint (a brick just set on the spot has not been through a step yet)."""
        if now:
            q = self.handles.brick_qpos[slot]
            offset = data.qpos[q : q + 3] - self.spawn.position
            mujoco.mju_quat2Mat(self._rot, data.qpos[q + 3 : q + 7])
            rot = self._rot.reshape(3, 3)
        else:
            body = self.body[slot]
            offset = data.xpos[body] - self.spawn.position
            rot = data.xmat[body].reshape(3, 3)
        return (
            math.hypot(offset[0], offset[1]),
            abs(float(offset[2])),
            tilt_of(rot),
            symmetric_yaw_error(yaw_of(rot), self.spawn.yaw),
        )

    def lies_at(self, data: mujoco.MjData, slot: int) -> Pose:
        """Where the brick in `slot` lies now (from its joint): its centre and yaw."""
        q = self.handles.brick_qpos[slot]
        mujoco.mju_quat2Mat(self._rot, data.qpos[q + 3 : q + 7])
        x, y, z = (float(v) for v in data.qpos[q : q + 3])
        return Pose(x, y, z, yaw_of(self._rot.reshape(3, 3)))

    def rests_on_spot(self, data: mujoco.MjData, slot: int, now: bool = False) -> bool:
        """Whether the brick in `slot` lies on the spot as spawned (a dropped brick that fell
        back where it was picked can simply be picked again); `now` as `spot_offset`'s."""
        across, height, tilt, turn = self.spot_offset(data, slot, now)
        return bool(
            across <= self.jitter * math.sqrt(2) + ON_SPOT_XY
            and height <= ON_SPOT_Z
            and tilt <= ON_SPOT_ANGLE
            and turn <= ON_SPOT_ANGLE
        )

    def off_spot(self, data: mujoco.MjData, slot: int) -> str:
        """How far the brick in `slot` lies from the spot as spawned, against what a pick
        allows, in words."""
        across, height, tilt, turn = self.spot_offset(data, slot)
        return (
            f"{across * 1000:.1f} mm across and {height * 1000:.1f} mm up or down from the spot, "
            f"tilted {math.degrees(tilt):.1f} deg and turned {math.degrees(turn):.1f} deg (a pick "
            f"allows {ON_SPOT_XY * 1000:g} mm across beyond the spawn jitter, "
            f"{ON_SPOT_Z * 1000:g} mm up or down, {math.degrees(ON_SPOT_ANGLE):g} deg)"
        )

    def in_the_way(self, data: mujoco.MjData, slot: int) -> bool:
        """Whether the brick in `slot` lies within `clearance` of the spawn volume: no brick
        is set on the spot while it is there."""
        return not self._apart(data, [self.model.body_geomadr[self.body[slot]]], self.clearance)

    def put_back(self, slot: int) -> None:
        """The brick in `slot` lies on the spot again: it is the one to pick next."""
        self.current = self.offered = slot

    def spawn_next(self, data: mujoco.MjData) -> int:
        """Teleport the next parked brick onto the spot, at rest; returns its slot."""
        slot = self.next_slot
        yaw = self.spawn.yaw
        offset = self.rng.uniform(-self.jitter, self.jitter, size=2) if self.jitter else (0.0, 0.0)
        self.handles.place_brick(
            data,
            slot,
            self.spawn.position + (offset[0], offset[1], 0.0),
            yaw_quaternion(yaw),
        )
        self.next_slot += 1
        self.current = self.offered = slot
        return slot
