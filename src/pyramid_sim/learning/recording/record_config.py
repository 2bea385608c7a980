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
from ...params import BETA, EPISODES, LINGER, NOISE, TAKEOVER, WORKERS
from ..action_modes.unbuilt import check_mode_for_robot
from ..task.observation_names import Observed
from ..task.randomize import check_parts
from ..task.ranges import check_image_size, control_steps
from ..task.spec import TaskSpec
from ..task.variation import DEFAULT_LEVEL, check_level

CAMERA_NAMES = "overview, front, top, left_wrist, right_wrist"
# The keywords of a recording's run, beside its task spec's: how many at once and where, and
# a DAgger round's driver
RUN_KEYWORDS = ("workers", "backend", "ray_address", "noise", "policy", "beta", "takeover")
# A task spec's fields a recording hands its environment as given, where not the default
FILM_FIELDS = ("footprints", "render_mode", "width", "height", "camera_name")
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
    # HG-DAgger: the learner's own actions kept while its hands are within `takeover` m of the
    # expert's way, the expert taking the rest of the span past it (None: pulled back to 5 mm)
    takeover: float | None = None
    # the bricks' poses (and the goals' fill, judged from them) observed: False for a policy
    # that sees the bricks through its cameras alone
    brick_poses: bool = True
    all_goals: bool = True  # every goal observed (False: each arm's next alone)

    @property
    def observed(self) -> Observed:
        """What the observation holds beyond the arms' own."""
        return Observed(self.brick_poses, self.all_goals)

    @property
    def task(self) -> TaskSpec:
        """The task spec its episodes are of: the environment takes it whole."""
        return TaskSpec.of(
            self.structure,
            variation=self.variation,
            fps=self.fps,
            limit_commands=self.limit_commands,
            image_size=self.image_size,
            randomize=self.randomize,
            action_mode=self.action_mode,
            linger=self.linger,
            **self.observed._asdict(),
            **self.options,
        )

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
        if self.takeover is not None:
            object.__setattr__(self, "takeover", TAKEOVER.checked(self.takeover))
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


def recording_of(
    task: TaskSpec, episodes: Any = 1, first_seed: Any = 0, **run: Any
) -> RecordConfig:
    """The recording of `task`'s episodes from `first_seed` on, `run` as RUN_KEYWORDS names
    them (ConfigError naming those for another; `beta` or `takeover` without a `policy` is
    refused)."""
    for name in run:
        if name not in RUN_KEYWORDS:
            raise ConfigError(f"record: unknown {name!r}; accepted {', '.join(RUN_KEYWORDS)}")
    for name in ("beta", "takeover"):
        if run.get(name) is not None and run.get("policy") is None:
            raise ConfigError(
                f"{name}: {run[name]!r} without a policy drives nothing; accepted {name} with a "
                "policy (a DAgger round), or neither"
            )
    config, _ = task.resolved()
    defaults = TaskSpec()
    film = {k: getattr(task, k) for k in FILM_FIELDS if getattr(task, k) != getattr(defaults, k)}
    options = {**task.sizes, **film, "arms": task.arms, "config": config}
    return RecordConfig(
        task.structure,
        options,
        episodes,
        first_seed,
        task.fps,
        task.cameras,
        task.image_size,
        task.variation,
        task.randomize,
        task.limit_commands,
        action_mode=task.action_mode,
        linger=task.linger,
        **task.observed._asdict(),
        **run,
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
