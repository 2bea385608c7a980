"""What the learning side observes and commands, defined once for the environment and any
recorder: the names and bounds of each entry, read from the robot's preset and the compiled
model. The command is the loop's own: both arms' joint targets, then each hand's finger gap,
arm by arm (`handles.ctrl_index` order)."""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from ...choices import CAMERAS, FPS_CHOICES
from ...core.poses import yaw_of
from ...errors import ConfigError
from ...params import IMAGE_SIZE_TEXT, image_size_fits
from ...physics import names as c
from ...physics.handles import SceneHandles
from ...robots import RobotDescription

DEFAULT_FPS = 25


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
    known = camera_names(robot)
    if isinstance(cameras, str):
        raise ConfigError(
            f"cameras: {cameras!r} is one name, not a sequence of them; accepted a tuple of "
            f"{', '.join(known)}"
        )
    cameras = tuple(cameras)
    for camera in cameras:
        if camera not in known:
            raise ConfigError(f"cameras: unknown {camera!r}; accepted {', '.join(known)}")
    if len(set(cameras)) != len(cameras):
        raise ConfigError(f"cameras: {', '.join(cameras)} names one twice; accepted each once")
    return cameras


def control_steps(fps: int, control_dt: float) -> int:
    """The build's control steps in one step at `fps` (a dataset's frame, an environment's
    step); ConfigError unless `fps` is one of FPS_CHOICES and divides the control rate."""
    steps = 1.0 / (fps * control_dt) if fps in FPS_CHOICES else 0.0
    if isinstance(fps, bool) or steps < 1.0 - 1e-9 or abs(steps - round(steps)) > 1e-9:
        raise ConfigError(
            f"fps: {fps!r}; accepted {', '.join(map(str, FPS_CHOICES))} (a divisor of the "
            f"build's {1.0 / control_dt:g} Hz control)"
        )
    return int(round(steps))


def check_image_size(size: tuple[int, int]) -> tuple[int, int]:
    """(height, width) as two whole numbers; ConfigError unless both are even and within
    IMAGE_HEIGHT and IMAGE_WIDTH."""
    try:
        height, width = (int(v) for v in size)
        whole = all(int(v) == v for v in size)
    except (TypeError, ValueError):
        height = width = 0
        whole = False
    if not (whole and image_size_fits(height, width)):
        raise ConfigError(f"image size: {size!r}; accepted (height, width), {IMAGE_SIZE_TEXT}")
    return height, width


def check_seed(seed: int) -> None:
    """ConfigError unless `seed` is a whole number from 0 to 2**32 - 1."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**32:
        raise ConfigError(f"seed: {seed!r} is out of range; accepted 0 to 2**32 - 1")
