"""What a recording is (`RecordConfig`, checked as it is made) and what it left (`Recorded`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ...choices import (
    RECORD_ACTION_MODES,
    RECORD_CAMERAS,
    RECORD_IMAGE_SIZE,
    RECORD_LINGER,
    in_words,
)
from ...config import MotionConfig
from ...errors import ConfigError
from ...jobs.backends import check_backend
from ...options import names_argument, plain_numbers
from ...params import BETA, EPISODES, LINGER, NOISE, WORKERS
from ..action_modes.registry import check_mode_for_robot
from ..task.layout import check_image_size, control_steps
from ..task.randomize import check_parts
from ..task.variation import DEFAULT_LEVEL, check_level

CAMERA_NAMES = "overview, front, top, left_wrist, right_wrist"
RANDOMIZED = "all, none, or some of the parts"


@dataclass(frozen=True)
class RecordConfig:
    """What a recording is: the build (structure, size and settings, as `build` takes them),
    how many episodes from which seed, and how they are filmed."""

    structure: str = "pyramid-even"
    options: dict[str, Any] = field(default_factory=dict)  # sizes and settings
    episodes: int = 1
    first_seed: int = 0
    fps: int = 25
    cameras: tuple[str, ...] = RECORD_CAMERAS
    image_size: tuple[int, int] = RECORD_IMAGE_SIZE
    variation: str = DEFAULT_LEVEL  # how episodes differ (learning/task/variation.py)
    randomize: tuple[str, ...] = ()  # parts of learning/task/randomize.py, drawn per episode
    limit_commands: bool = True  # the environment's: commands through the motion generator
    workers: int = 1  # episodes filmed at once, each in a process of its own
    backend: str = "process"  # or ray: the episodes as Ray tasks
    ray_address: str | None = None  # with ray: a cluster's (default: a Ray started here)
    noise: float = 0.0  # rad: DART's offset on the executed joints, the expert's own the label
    action_mode: str = "joint"  # or relative: each joint's action its change from the state
    linger: float = RECORD_LINGER  # s filmed after the build succeeds: the last release taught
    # DAgger (dagger.py): a policy (as `evaluate --policy` takes one) drives the spans the
    # expert does not (the expert's share `beta`), the expert labelling every frame
    policy: str | None = None
    beta: float = 0.5
    # the bricks' poses (and the goals' fill, judged from them) observed: False for a policy
    # that sees the bricks through its cameras alone
    brick_poses: bool = True
    all_goals: bool = True  # every goal observed (False: each arm's next alone)

    def __post_init__(self) -> None:
        for name in ("episodes", "first_seed", "fps", "workers", "noise", "linger", "beta"):
            object.__setattr__(self, name, plain_numbers({name: getattr(self, name)})[name])
        for name, accepted in (("cameras", CAMERA_NAMES), ("randomize", RANDOMIZED)):
            object.__setattr__(self, name, names_argument(getattr(self, name), name, accepted))
        object.__setattr__(self, "image_size", check_image_size(self.image_size))
        EPISODES.check_whole(self.episodes)
        control_steps(self.fps, MotionConfig().control_dt)
        if not self.cameras and tuple(self.image_size) != RECORD_IMAGE_SIZE:
            raise ConfigError(
                f"image size: {tuple(self.image_size)} with no camera films nothing; accepted "
                "a camera to film at it, or the default size"
            )
        check_level(self.variation)
        if not check_parts(self.randomize):  # "none" is no part: kept as no parts are
            object.__setattr__(self, "randomize", ())
        WORKERS.check_whole(self.workers)
        check_backend(self.backend, self.ray_address)
        NOISE.check(self.noise)
        LINGER.check(self.linger)
        BETA.check(self.beta)
        if self.policy is not None and (not isinstance(self.policy, str) or not self.policy):
            raise ConfigError(
                f"policy: {self.policy!r} is not one; accepted a lerobot checkpoint folder, "
                "zero, random or module:factory (as evaluate takes them)"
            )
        if self.action_mode not in RECORD_ACTION_MODES:
            raise ConfigError(
                f"action mode: {self.action_mode!r} is not recorded; accepted "
                + in_words(RECORD_ACTION_MODES)
            )
        robot = getattr(self.options.get("config"), "robot", None)
        if robot is not None:  # refused naming the modes record takes
            check_mode_for_robot(self.action_mode, robot, RECORD_ACTION_MODES)
        if not 0 <= self.first_seed <= 2**32 - self.episodes:  # every episode's seed < 2**32
            raise ConfigError(
                f"seed: {self.first_seed} is out of range; accepted 0 to 2**32 - "
                f"{self.episodes} (the last of {self.episodes} episodes' seeds below 2**32)"
            )


@dataclass(frozen=True)
class Recorded:
    """What a recording left: the dataset's folder, its episodes and frames, and how many
    episodes this run added."""

    root: Path
    episodes: int
    frames: int
    added: int
    failed: tuple[int, ...]  # episodes whose build did not succeed (they are kept)
