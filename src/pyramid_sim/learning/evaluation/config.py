"""What an evaluation is: the policy, the task, the episodes and their seeds (held out from
recordings), how many are filmed, and how many run at once."""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any

from ...choices import EVAL_FIRST_SEED
from ...config import MotionConfig
from ...errors import ConfigError
from ...jobs.backends import check_backend
from ...options import plain_numbers
from ...params import EPISODES, MAX_STEPS, WORKERS
from ..task.layout import check_seed
from ..task.ranges import control_steps
from ..task.spec import SIZES, TaskSpec
from ..task.variation import DEFAULT_LEVEL, check_level

EVAL_SEED = EVAL_FIRST_SEED  # recordings start at 0 (`record --seed`)
SPLIT = (
    "evaluation seeds first_seed..first_seed+episodes-1 (default from 100000); recordings "
    "use seeds from 0 (default), so they never overlap for recordings of fewer than 100000 "
    "episodes"
)


@dataclass(frozen=True)
class EvaluateConfig:
    """What an evaluation is: the policy, the task (structure, size and settings as `build`
    takes them, the variation and step rate), how many episodes from which seed, and how many
    of the first are filmed."""

    policy: str = "expert"
    structure: str = "pyramid-even"
    options: dict[str, Any] = field(default_factory=dict)  # sizes and settings
    variation: str = DEFAULT_LEVEL
    fps: int = 25
    episodes: int = 10
    first_seed: int = EVAL_SEED
    videos: int = 0  # the first episodes filmed from the overview camera
    max_steps: int | None = None  # an episode's step limit (default: `step_limit`)
    action_mode: str = "joint"  # the policy's: one of choices.ACTION_MODES
    workers: int = 1  # episodes run at once, each worker with its environment and policy
    backend: str = "process"  # or ray: the episodes as Ray tasks
    ray_address: str | None = None  # with ray: a cluster's (default: a Ray started here)

    def __post_init__(self) -> None:
        for name in ("fps", "episodes", "first_seed", "videos", "max_steps", "workers"):
            object.__setattr__(self, name, plain_numbers({name: getattr(self, name)})[name])
        EPISODES.check_whole(self.episodes)
        WORKERS.check_whole(self.workers)
        check_backend(self.backend, self.ray_address)
        check_level(self.variation)
        control_steps(self.fps, MotionConfig().control_dt)
        check_seed(self.first_seed)
        if self.first_seed > 2**32 - self.episodes:  # the last episode's seed below 2**32
            raise ConfigError(
                f"seed: {self.first_seed} is out of range; accepted 0 to 2**32 - "
                f"{self.episodes} (the last of {self.episodes} episodes' seeds below 2**32)"
            )
        if self.max_steps is not None:
            MAX_STEPS.check_whole(self.max_steps)  # 1.5 steps reached Gymnasium's TimeLimit
        if not 0 <= self.videos <= self.episodes:
            raise ConfigError(
                f"video: {self.videos} episodes filmed; accepted 0 to the {self.episodes} run"
            )


# A task spec's fields an evaluation holds itself (the rest it hands its environment beside
# its size and the policy's views, where not the default)
OWN = ("structure", "robot", "arms", "variation", "fps", "action_mode", "settings", "config")
OWN_FIELDS = (*OWN, *SIZES)


def evaluation_of(
    policy: str,
    task: TaskSpec,
    shown: dict[str, Any],
    episodes: Any = 10,
    first_seed: Any = EVAL_SEED,
    videos: Any = 0,
    **run: Any,
) -> EvaluateConfig:
    """The evaluation of `policy` on `task`'s episodes: `shown` the size and the views
    evaluation.json lists (a checkpoint's cameras), `run` the evaluation's max_steps,
    workers, backend and ray_address."""
    config, _ = task.resolved()
    defaults = TaskSpec()
    others = {
        k: getattr(task, k)
        for k in (f.name for f in fields(TaskSpec) if f.name not in OWN_FIELDS)
        if k not in shown and getattr(task, k) != getattr(defaults, k)
    }
    options = {**shown, **others, "arms": task.arms, "config": config}
    return EvaluateConfig(
        policy,
        task.structure,
        options,
        task.variation,
        task.fps,
        episodes,
        first_seed,
        videos,
        action_mode=task.action_mode,
        **run,
    )
