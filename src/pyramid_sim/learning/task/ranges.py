"""The ranges an episode's options are checked against that need no scene: the step rate, an
image's size and the cameras' names (the same for every robot: the scene's three and a wrist
camera on each arm). MuJoCo-free, so a task spec is checked before any physics is imported."""

from __future__ import annotations

from typing import Any

from ...choices import ARMS, CAMERAS, FPS_CHOICES
from ...errors import ConfigError
from ...params import IMAGE_SIZE_TEXT, image_size_fits

DEFAULT_FPS = 25
# Every camera an observation can hold, by the name a dataset gives it.
CAMERA_NAMES: tuple[str, ...] = (*CAMERAS, *(f"{arm}_wrist" for arm in ARMS))


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


def check_camera_names(cameras: Any, known: tuple[str, ...] = CAMERA_NAMES) -> tuple[str, ...]:
    """The cameras as a tuple; ConfigError for a camera that is not one of `known`, one named
    twice, or a single name where a sequence of them is asked."""
    if isinstance(cameras, str):
        raise ConfigError(
            f"cameras: {cameras!r} is one name, not a sequence of them; accepted a tuple of "
            f"{', '.join(known)}"
        )
    try:
        cameras = tuple(cameras)
    except TypeError:
        raise ConfigError(
            f"cameras: {cameras!r} is not a sequence; accepted a tuple of {', '.join(known)}"
        ) from None
    for camera in cameras:
        if camera not in known:
            raise ConfigError(f"cameras: unknown {camera!r}; accepted {', '.join(known)}")
    if len(set(cameras)) != len(cameras):
        raise ConfigError(f"cameras: {', '.join(cameras)} names one twice; accepted each once")
    return cameras
