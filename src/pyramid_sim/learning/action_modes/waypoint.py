"""The environment's `action_mode="waypoint"`: each arm's tool pose to go to (x, y, z, yaw in
the world) and finger gap. A waypoint says where a move ends, not how far a step goes, so every
action carries its goal (the brick on the spot, the place it is for) in centimetres, where a
step's change of joints or tool carries a few milliradians of it.

The arm goes there as the `ee` mode's targets move: straight, at most the hand's free speed,
at its slow speed over the last `NEAR` of the way (a brick is met slowly, as the build's own
servo moves meet it), its yaw at the hand's turn rate; the IK, its limits, the leash, the box
and the floor are the `ee` mode's, and its joints go through the motion generator. A waypoint
that jitters or jumps from one action to the next moves the target no faster for it. Where the
robot bounds its hand's acceleration (Baxter's), the target also gains and sheds its speed no
faster than that, braking in time to stop where the waypoint is. The
gap says open or closed, and the hand grips and releases as the scripted builder's does
(gripper_switch.py).
"""

from __future__ import annotations

import math

import numpy as np
from gymnasium import spaces

from ...config import SimConfig
from ...core.poses import Pose
from ...core.primitives import StepKind
from ...physics import names as c
from ...physics.loop import BuildLoop
from ..task.layout import Layout
from .ee import EndEffectorControl, end_effector
from .gripper_switch import GripperSwitch
from .hand_mode import HandPoseMode
from .mode import ExpertMove, ModeParts, Waypoints

FIELDS = ("x", "y", "z", "yaw", "gripper")
NEAR = 0.05  # m of a move's end covered at the slow speed
LAG = 0.1  # s: near its end a move slows as a first-order lag, so a waypoint's jitter is smoothed
REACH = 2.0  # m: the space's bound on a waypoint's x, y and z (the box bounds them per episode)


class WaypointControl:
    """Actions of (x, y, z, yaw, gripper gap) per arm, left first: where each arm's tool centre
    goes, `steps` control steps of `control_dt` an environment step."""

    def __init__(
        self,
        ee: EndEffectorControl,
        layout: Layout,
        speeds: tuple[float, float, float],
        control_dt: float,
        hands: GripperSwitch,
        acceleration: float = math.inf,
    ) -> None:
        self.ee = ee
        self.hands = hands
        self.speed, self.slow_speed, self.turn_rate = speeds
        self.dt = control_dt
        self.acceleration = acceleration  # m/s^2 of the target's; inf: speeds change at once
        self._velocity = np.zeros((len(c.ARMS), 3))  # each target's, where it is bounded
        low, high = [], []
        for gap in ee.gaps:
            low += [-REACH, -REACH, 0.0, -2 * math.pi, layout.low[gap]]
            high += [REACH, REACH, REACH, 2 * math.pi, layout.high[gap]]
        self.space = spaces.Box(
            np.array(low, dtype=np.float32), np.array(high, dtype=np.float32), dtype=np.float32
        )
        self.names = tuple(f"{arm}/{f}" for arm in c.ARMS for f in FIELDS)

    def reset(self, loop: BuildLoop) -> None:
        """Aim each arm where its tool centre is (the `ee` mode's box and floor), its hand as
        it is commanded."""
        self.ee.reset(loop)
        self._velocity[:] = 0.0
        gaps = loop.data.ctrl[loop.handles.ctrl_index][self.ee.gaps]
        self.hands.reset([float(g) for g in gaps])

    def command(self, loop: BuildLoop, action: np.ndarray) -> np.ndarray:
        """The joint command for one control step towards the waypoints of `action`."""
        moves = np.zeros(10)
        for k, arm in enumerate(c.ARMS):
            x, y, z, yaw, gap = (float(v) for v in action[5 * k : 5 * k + 5])
            t = self.ee.targets[arm]
            way = np.array([x - t.x, y - t.y, z - t.z])
            distance = float(np.linalg.norm(way))
            speed = min(self.slow_speed if distance <= NEAR else self.speed, distance / LAG)
            if math.isfinite(self.acceleration):
                way = self._accelerated(k, way, distance, speed)
            elif distance > speed * self.dt:
                way *= speed * self.dt / distance
            turn = math.remainder(yaw - t.yaw, 2 * math.pi)
            turn = max(-self.turn_rate * self.dt, min(self.turn_rate * self.dt, turn))
            moves[5 * k : 5 * k + 5] = [*way, turn, self.hands.command(k, gap, self.dt)]
        return self.ee.move(loop, moves)

    def _accelerated(self, k: int, way: np.ndarray, distance: float, speed: float) -> np.ndarray:
        """Arm `k`'s target's move this control step toward the end of `way`, at `speed` or
        what braking at the bound still stops from, its velocity changed by at most the
        bound's share of the step."""
        speed = min(speed, math.sqrt(2.0 * self.acceleration * distance))
        wanted = way * (speed / distance) if distance > 0.0 else np.zeros(3)
        change = wanted - self._velocity[k]
        most = self.acceleration * self.dt
        size = float(np.linalg.norm(change))
        if size > most:
            change *= most / size
        velocity = self._velocity[k] + change
        move = velocity * self.dt
        if float(np.linalg.norm(move)) > distance:  # there within this step: stop on it
            move, velocity = way, way / self.dt
        self._velocity[k] = velocity
        return move

    def expert(self, loop: BuildLoop) -> np.ndarray:
        """Where the scripted builder's current move ends for each arm (of a move up, over and
        down, the corner it heads for), aimed as its closed loop aims, and its hand open or
        closed as it is gripping or letting go."""
        action: list[float] = []
        for arm in c.ARMS:
            runner = loop.dispatch.runners[arm]
            pose = runner.pose
            step, path = runner.current, runner.path
            if step is not None and step.kind is StepKind.MOVE and path is not None:
                assert step.pose is not None
                pose = path.heading(runner.elapsed).with_yaw(step.pose.yaw)
            if loop.closure is not None:
                pose = loop.closure.aim(arm, pose)
            action += [pose.x, pose.y, pose.z, pose.yaw, self.hands.label(runner)]
        return np.array(action)

    def hold(self, loop: BuildLoop) -> np.ndarray:
        """Stay where aimed, the hands as they are."""
        action: list[float] = []
        for k, arm in enumerate(c.ARMS):
            t: Pose = self.ee.targets[arm]
            action += [t.x, t.y, t.z, t.yaw, self.hands.held(k)]
        return np.array(action)


def waypoints(config: SimConfig, layout: Layout, steps: int) -> WaypointControl:
    """The `waypoint` action mode's controller for the robot and settings."""
    motion = config.hand_motion
    return WaypointControl(
        end_effector(config, layout, steps),
        layout,
        (motion.speed, motion.slow_speed, motion.turn_rate),
        motion.control_dt,
        GripperSwitch(config, len(c.ARMS)),
        config.robot_description.hand_acceleration,
    )


def _float32(waypoint: np.ndarray) -> np.ndarray:
    return waypoint.astype(np.float32)


class WaypointMode(HandPoseMode):
    """Actions of where each hand's tool centre goes and its finger gap, through the `ee`
    mode's IK (`WaypointControl`), then the motion generator."""

    fields: tuple[str, ...] = FIELDS

    def __init__(self, parts: ModeParts) -> None:
        control = waypoints(parts.config, parts.layout, parts.steps)
        super().__init__(parts, control, ("x", "y", "z"))

    def expert(self, move: ExpertMove) -> np.ndarray:
        """Where the builder's move ends, a waypoint that stays once the build is done."""
        return self.control.expert(move.loop).astype(np.float32)

    def waypoints(self, action: np.ndarray) -> Waypoints | None:
        return action, _float32
