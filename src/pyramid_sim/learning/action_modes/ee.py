"""The environment's `action_mode="ee"`: each arm's tool-pose change and finger gap, turned
into the joint command by the build's own IK, with its joint, speed, acceleration and
collision limits.

The action space is what the robot can follow: an environment step moves a target at most as
far as the build's own free moves go in that time (the hand's speed and turn rate), and a
target never runs ahead of the tool by more than `LEASH` (`TURN_LEASH`), so holding an action
at its bound cannot wind the IK up against the arm's reach, and never lower than a grip on a
brick lying on the table, so it cannot drive the hand into the table.
"""

from __future__ import annotations

import math

import numpy as np
from gymnasium import spaces

from ...config import SimConfig
from ...core.poses import Pose
from ...physics import names as c
from ...physics.loop import BuildLoop
from ...physics.reach import plan_poses
from ..task.layout import Layout
from .hand_mode import HandPoseMode
from .mode import ExpertMove, ModeParts, Waypoints

FIELDS = ("dx", "dy", "dz", "dyaw", "gripper")
LEASH = 0.01  # m a target may lead the tool centre, along each axis
TURN_LEASH = 0.05  # rad a target's yaw may lead the hand's
SHARE = 0.75  # of the hand's speed and turn rate an action moves a target at most
MARGIN = 0.08  # m beyond the expert's poses, each way, a target may go
TURN_MARGIN = 0.3  # rad beyond the expert's yaws


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


def _near(yaw: float, reference: float) -> float:
    """`yaw` turned by whole turns to within half a turn of `reference` (as it is if it is)."""
    return yaw if abs(yaw - reference) <= math.pi else reference + _wrap(yaw - reference)


class EndEffectorControl:
    """Actions of (dx, dy, dz, dyaw, gripper gap) per arm, left first, moving each arm's
    tool-centre target from where it was aimed the step before, across `steps` control steps
    of `control_dt` each."""

    def __init__(
        self,
        layout: Layout,
        speed: float,
        turn_rate: float,
        control_dt: float,
        steps: int,
        floor: float,
    ) -> None:
        self.floor = floor  # m: the lowest a target goes, a grip on a brick lying on the table
        self.gaps = [i for i, name in enumerate(layout.names) if name.endswith("/gripper")]
        self.steps = steps
        reach, turn = (SHARE * v * control_dt * steps for v in (speed, turn_rate))
        low, high = [], []
        for gap in self.gaps:
            low += [-reach] * 3 + [-turn, layout.low[gap]]
            high += [reach] * 3 + [turn, layout.high[gap]]
        self.space = spaces.Box(
            np.array(low, dtype=np.float32), np.array(high, dtype=np.float32), dtype=np.float32
        )
        self.names = tuple(f"{arm}/{f}" for arm in c.ARMS for f in FIELDS)
        self.targets: dict[str, Pose] = {}
        self.box: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        self.yaw_ref: dict[str, float] = {}

    def reset(self, loop: BuildLoop) -> None:
        """Aim each arm where its tool centre is; each arm's targets are kept within the box
        (x, y, z, yaw) of every pose the expert's build of this plan goes through, `MARGIN`
        (`TURN_MARGIN`) wider: where the arm works well inside its reach and its wrist's
        range, whichever way the hand comes. Yaws are kept within half a turn of the arm's
        reference yaw: an arm whose grasps cross a half turn (the SO-101 pair's right) has
        one arc of them, not the circle's rest between their wrapped values."""
        self.targets = {arm: loop.ik.tcp_pose(arm) for arm in c.ARMS}
        poses: dict[str, list[Pose]] = {arm: [self.targets[arm]] for arm in c.ARMS}
        for arm, _, pose in plan_poses(loop.plan, loop.config):
            poses[arm].append(pose)
        self.box = {}
        robot = loop.config.robot_description
        self.yaw_ref = {arm: robot.arms[arm].yaw_reference for arm in c.ARMS}
        for side, seen in poses.items():
            ref = self.yaw_ref[side]  # yaws as turns from the arm's own: one arc, not its rest
            values = np.array([[p.x, p.y, p.z, _near(p.yaw, ref)] for p in seen])
            margin = np.array([MARGIN, MARGIN, MARGIN, TURN_MARGIN])
            self.box[side] = (values.min(axis=0) - margin, values.max(axis=0) + margin)

    def command(self, loop: BuildLoop, action: np.ndarray) -> np.ndarray:
        """The joint command for one control step of `action` (a share of the environment
        step's move): the IK aimed at the moved targets, kept on their leash, and stepped once
        (mink.NoSolutionFound if it has no motion within the limits)."""
        return self.move(loop, action * np.tile([1.0 / self.steps] * 4 + [1.0], len(c.ARMS)))

    def move(self, loop: BuildLoop, moves: np.ndarray) -> np.ndarray:
        """The joint command for one control step that moves each arm's target by its
        (dx, dy, dz, dyaw) in `moves` and sets its gap, as `command` does."""
        for k, arm in enumerate(c.ARMS):
            dx, dy, dz, dyaw, _ = moves[5 * k : 5 * k + 5]
            t, tool = self.targets[arm], loop.ik.tcp_pose(arm)
            yaw = tool.yaw + float(np.clip(_wrap(t.yaw + dyaw - tool.yaw), -TURN_LEASH, TURN_LEASH))
            aim = np.clip(
                [t.x + dx, t.y + dy, t.z + dz, yaw],
                [tool.x - LEASH, tool.y - LEASH, tool.z - LEASH, -np.inf],
                [tool.x + LEASH, tool.y + LEASH, tool.z + LEASH, np.inf],
            )
            low, high = self.box[arm]
            aim[3] = _near(aim[3], self.yaw_ref[arm])
            x, y, z, yaw = (float(v) for v in np.clip(aim, low, high))
            self.targets[arm] = Pose(x, y, max(self.floor, z), yaw)
            loop.ik.set_target(arm, self.targets[arm])
        loop.ik.step()
        command = loop.command().copy()
        command[self.gaps] = moves[[4, 9]]
        return command

    def expert(self, loop: BuildLoop) -> np.ndarray:
        """The scripted builder's move, where its primitives aim each arm now, as such an
        action (the environment clips it to the space)."""
        action: list[float] = []
        for arm in c.ARMS:
            runner, t = loop.dispatch.runners[arm], self.targets[arm]
            p = runner.pose
            action += [p.x - t.x, p.y - t.y, p.z - t.z, _wrap(p.yaw - t.yaw), runner.gap]
        return np.array(action)

    def hold(self, loop: BuildLoop) -> np.ndarray:
        """Stay where aimed, the hands as they are commanded."""
        gaps = loop.data.ctrl[loop.handles.ctrl_index][self.gaps]
        return np.array([0.0, 0.0, 0.0, 0.0, gaps[0], 0.0, 0.0, 0.0, 0.0, gaps[1]])


def end_effector(config: SimConfig, layout: Layout, steps: int) -> EndEffectorControl:
    """The `ee` action mode's controller for the robot and settings."""
    motion, robot = config.hand_motion, config.robot_description
    floor = config.layout.table_top_z + config.brick.height / 2 + robot.grasp_height
    return EndEffectorControl(
        layout, motion.speed, motion.turn_rate, motion.control_dt, steps, floor
    )


class EndEffectorMode(HandPoseMode):
    """Actions of each hand's tool-pose change and finger gap, through the build's own IK
    (`EndEffectorControl`), then the motion generator."""

    fields = FIELDS

    def __init__(self, parts: ModeParts) -> None:
        control = end_effector(parts.config, parts.layout, parts.steps)
        super().__init__(parts, control, ("dx", "dy", "dz"))

    def expert(self, move: ExpertMove) -> np.ndarray:
        """The builder's move while it moves; once it has stopped, stay where aimed."""
        action = self.control.expert if move.moving else self.control.hold
        return action(move.loop).astype(np.float32)

    def waypoints(self, action: np.ndarray) -> Waypoints | None:
        return None
