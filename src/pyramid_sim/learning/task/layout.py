"""What the learning side observes and commands, defined once for the environment and any
recorder: the names and bounds of each entry, read from the robot's preset and the compiled
model. The command is the loop's own: both arms' joint targets, then each hand's finger gap,
arm by arm (`handles.ctrl_index` order)."""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from ...choices import CAMERAS
from ...core.poses import yaw_of
from ...errors import ConfigError
from ...physics import names as c
from ...physics.handles import SceneHandles
from ...robots import RobotDescription
from .ranges import check_camera_names


@dataclass(frozen=True)
class Layout:
    """Names and bounds of the state and the action (the same vector layout), and how many
    bricks the magazine holds."""

    names: tuple[str, ...]  # "left/panda_joint1", ..., "left/gripper", ..., "right/gripper"
    low: np.ndarray
    high: np.ndarray
    bricks: int

    @property
    def size(self) -> int:
        return len(self.names)

    @property
    def joints(self) -> np.ndarray:
        """True at the arm joints' entries, False at the finger gaps'."""
        return np.array([not name.endswith("/gripper") for name in self.names])


def layout(model: mujoco.MjModel, handles: SceneHandles, robot: RobotDescription) -> Layout:
    """The layout of a compiled scene: each arm's joints at their joint ranges, then its
    gripper's finger gap from closed (0) to both fingers' full travel."""
    names: list[str] = []
    low: list[float] = []
    high: list[float] = []
    for arm in c.ARMS:
        for joint in robot.arms[arm].joints:
            lo, hi = model.joint(joint).range
            names.append(f"{arm}/{joint.rsplit('/', 1)[-1]}")
            low.append(float(lo))
            high.append(float(hi))
        names.append(f"{arm}/gripper")
        low.append(0.0)
        high.append(2 * robot.finger_stroke)
    return Layout(tuple(names), np.array(low), np.array(high), handles.n_bricks)


def state(data: mujoco.MjData, handles: SceneHandles, out: np.ndarray) -> np.ndarray:
    """Both arms' joint positions and each hand's finger gap (its fingers' travel, each by
    its gain: a jaw's angle times its lever), in the layout's order, written into `out`."""
    k = 0
    for arm in c.ARMS:
        q = handles.arm_qpos[arm]
        out[k : k + len(q)] = data.qpos[q]
        k += len(q)
        fingers = zip(handles.finger_qpos[arm], handles.finger_gains)
        out[k] = sum(abs(gain * data.qpos[f]) for f, gain in fingers)
        k += 1
    return out


def tools(data: mujoco.MjData, handles: SceneHandles) -> np.ndarray:
    """Each hand's tool centre and yaw (x, y, z, yaw), left first, as measured now."""
    return np.array(
        [
            [
                *data.site_xpos[handles.tcp_site[arm]],
                yaw_of(data.site_xmat[handles.tcp_site[arm]].reshape(3, 3)),
            ]
            for arm in c.ARMS
        ]
    )


def brick_index(handles: SceneHandles) -> np.ndarray:
    """The qpos addresses of every magazine brick's position and orientation (n x 7, in
    magazine order): `data.qpos[brick_index(h)]` is the `bricks` observation."""
    return np.array([np.arange(q, q + 7) for q in handles.brick_qpos])


def camera_names(robot: RobotDescription) -> dict[str, str]:
    """The cameras an observation can hold, by the name a dataset gives them, to the model's
    camera names: the scene's three and a wrist camera on each hand."""
    named: dict[str, str] = {camera: camera for camera in CAMERAS}
    for arm, description in robot.arms.items():
        named[f"{arm}_wrist"] = description.wrist_camera
    return named


def check_cameras(cameras: tuple[str, ...], robot: RobotDescription) -> tuple[str, ...]:
    """The cameras as a tuple; ConfigError for a camera that is not one of `camera_names`,
    one named twice, or a single name where a sequence of them is asked."""
    return check_camera_names(cameras, tuple(camera_names(robot)))


def check_seed(seed: int) -> None:
    """ConfigError unless `seed` is a whole number from 0 to 2**32 - 1."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**32:
        raise ConfigError(f"seed: {seed!r} is out of range; accepted 0 to 2**32 - 1")
