"""The Python API for notebooks and scripts: `plan` (pure) and `build` (physics).

    import pyramid_sim
    result = pyramid_sim.build("pyramid-even", layers=2, friction=0.8)
    result.success, result.bricks_placed, [b.error_xy_mm for b in result.bricks]

Settings are keywords: the parameter table's names (friction, brick_mass, grip_force,
pad_friction), spawn_jitter_mm, seed, robot and schedule, or a whole `config=SimConfig(...)`. Everything is
validated before any physics runs; a bad value raises ConfigError naming its accepted range.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .choices import (
    EVAL_FIRST_SEED,
    RECORD_CAMERAS,
    RECORD_FPS,
    RECORD_IMAGE_SIZE,
    RECORD_LINGER,
    ArmChoice,
)
from .config import SimConfig, VideoConfig, check_film
from .core.plan import Plan, make_plan
from .errors import ConfigError, MachineError
from .learning.recording.record_config import RUN_KEYWORDS
from .learning.task.spec import TaskSpec, check_keywords, strict_bool
from .options import (
    callback_argument,
    resolve,
    settings,
    structure,
)
from .output import written
from .output.result import BuildResult

__all__ = ["build", "evaluate", "plan", "record", "settings", "structure"]

if TYPE_CHECKING:  # the recorder and evaluation need MuJoCo: imported when they run
    from .learning.evaluation.evaluate import Evaluation
    from .learning.recording.record import Recorded


def plan(
    name: str = "pyramid-even",
    *,
    arms: ArmChoice = "both",
    config: SimConfig | None = None,
    **options: Any,
) -> Plan:
    """The build plan: every brick's target, arm and order, and the spawn pose. `options` are
    the structure's size (layers, bricks, width, towers, goals) and settings. No physics (and
    no reach check: `build` does that)."""
    config, spec = resolve(name, config, options, own=("arms",))
    return make_plan(spec, config, arms)


def build(
    name: str = "pyramid-even",
    *,
    arms: ArmChoice = "both",
    config: SimConfig | None = None,
    video: str | Path | None = None,
    snapshot: str | Path | None = None,
    video_config: VideoConfig | None = None,
    out: str | Path | None = None,
    on_start: Callable[[Plan], Any] | None = None,
    on_placed: Callable[[int], Any] | None = None,
    on_frame: Callable[[int], Any] | None = None,
    **options: Any,
) -> BuildResult:
    """Build the structure in the physics and return its judged result; `options` as for
    `plan`. With `video` (an .mp4 path) or `snapshot` (a .png path) the build is rendered
    headless (whether or not MuJoCo was imported first), and a machine without a headless GL
    backend is refused before any physics runs. With `out`, the result is saved as
    `out/result.json` (as `pyramid-sim build` does), its poses as `out/replay.npz`.

    The folders written (`out`, the video's, the still's) are held against a second run while
    this one runs, and removed if it made them and fails. Hooks: `on_start(plan)` once the
    plan is reachable and the folders held, `on_placed(n)` at n bricks, `on_frame(n)` at n frames."""
    config, spec = resolve(name, config, options, own=BUILD_KEYWORDS)
    for hook, what in ((on_start, "on_start"), (on_placed, "on_placed"), (on_frame, "on_frame")):
        callback_argument(hook, what)
    if video_config is not None and not isinstance(video_config, VideoConfig):
        raise ConfigError(
            f"video_config: {video_config!r} is not a VideoConfig; accepted "
            "pyramid_sim.VideoConfig(...) or None"
        )
    vc = video_config or VideoConfig()
    if video is not None:
        check_film(vc, config)
    films = written.films(vc, video, snapshot)
    folders = written.build_folders(written.results_folder(out), films)
    prepare, run_build = _physics(render=bool(films))
    plan = prepare(spec, config, arms)
    with written.held(folders):
        if on_start is not None:
            on_start(plan)
        result: BuildResult = run_build(
            plan,
            config,
            on_placed=on_placed,
            video=films.get(".mp4"),
            on_frame=on_frame,
            snapshot=films.get(".png"),
            replay=None if out is None else Path(out) / "replay.npz",
        )
        if out is not None:
            result.save(Path(out) / "result.json")
    return result


BUILD_KEYWORDS = (
    "arms",
    "video",
    "snapshot",
    "video_config",
    "out",
    "on_start",
    "on_placed",
    "on_frame",
)


def _physics(render: bool) -> tuple[Callable[..., Plan], Callable[..., BuildResult]]:
    """The reach check and the build, imported (MuJoCo with them) under a headless GL backend
    chosen first: the one MuJoCo binds on its first import, and the one the renderer makes its
    context with after it. MachineError if `render` and none can be had, or MuJoCo cannot
    load under it."""
    from .output.gl_backend import choose_gl_backend, import_physics_for_rendering

    try:
        choose_gl_backend()
    except MachineError:
        if render:
            raise
    try:
        from .jobs.build import run_build
        from .physics.reach import prepare
    except (ImportError, AttributeError, RuntimeError):
        if render:
            import_physics_for_rendering()  # MachineError naming the backend, if MuJoCo failed
        raise
    return prepare, run_build


def _prepare_gl(render: bool) -> None:
    """Choose the headless GL backend: before MuJoCo's first import it is the backend MuJoCo
    binds, and after it the one the renderer makes its context with. MachineError if `render`
    and none can be had."""
    from .output.gl_backend import choose_gl_backend, import_physics_for_rendering

    try:
        choose_gl_backend()
    except MachineError:
        if render:
            raise
    if render:
        import_physics_for_rendering()


# A recording's defaults where a task spec's differ: a default recording's frame rate,
# cameras, image size and linger (lerobot's plugin evaluates with the same)
RECORD_DEFAULTS = {
    "fps": RECORD_FPS,
    "cameras": RECORD_CAMERAS,
    "image_size": RECORD_IMAGE_SIZE,
    "linger": RECORD_LINGER,
}
RECORD_OWN = ("out", "episodes", "seed", "on_frame", "on_episode", "repair")


def record(
    task: TaskSpec | str = "pyramid-even",
    *old_order: Any,
    out: str | Path | None = None,
    episodes: int = 1,
    seed: int = 0,
    on_frame: Any = None,
    on_episode: Any = None,
    **options: Any,
) -> Recorded:
    """Record the expert's episodes of `task` (a TaskSpec, or a structure's name with the
    spec's keywords in `options`: its fields, sizes and settings) as a LeRobot dataset (v3.0) in
    the folder `out`: `episodes` builds from seeds `seed`, `seed` + 1, ... By name, a
    recording's defaults stand where a spec's differ (25 fps, the overview and wrist cameras at
    224 x 224, 2 s of linger). The run's own keywords: `workers` at once (`backend="ray"`: Ray
    tasks, at `ray_address`); `noise`, DART's (rad on each joint in the joint modes, m on each
    hand's x, y, z in the hand modes); with `policy` (as `evaluate` takes one), a DAgger round:
    it drives the 2 s spans the expert does not (a share `beta`), the expert labelling every
    frame. Episodes in `out` are kept; a folder holding anything else, or a damaged episode
    (unless `repair=True`), is refused. `on_frame(episode, frames so far)` and
    `on_episode(episodes in the dataset)` hear progress."""
    folder = _dataset_folder(old_order, out)
    run = {k: options.pop(k) for k in RUN_KEYWORDS if k in options}
    repair = strict_bool("repair", options.pop("repair", False))
    check_keywords(options, (*RUN_KEYWORDS, *RECORD_OWN))
    if not isinstance(task, TaskSpec):
        task = TaskSpec.of(task, **{**RECORD_DEFAULTS, **options})
    elif options:
        TaskSpec.of(task, **options)  # ConfigError: a whole spec takes no keyword beside it
    for hook, what in ((on_frame, "on_frame"), (on_episode, "on_episode")):
        callback_argument(hook, what)
    from .learning.recording.record_config import recording_of

    wanted = recording_of(task, episodes, seed, **run)  # checked before MuJoCo loads
    from .learning.recording.record import record as run_recording

    _prepare_gl(render=bool(wanted.cameras))
    from .learning.evaluation.policies import make_policy

    with written.held([(folder, "out")]):
        return run_recording(folder, wanted, on_frame, on_episode, make_policy, repair=repair)


def _dataset_folder(old_order: tuple[Any, ...], out: str | Path | None) -> Path:
    """`record`'s folder, given as out= after the structure (ConfigError for the old call,
    record(folder, structure), or none)."""
    if old_order or out is None:
        raise ConfigError(
            "out: record takes the structure first and the dataset's folder as out=, as "
            "build, plan and evaluate take the structure first; accepted "
            "record('pyramid-even', out='runs/dataset', ...), not record(folder, structure)"
        )
    folder = written.out_folder(out)
    assert folder is not None
    return folder


# evaluate's own keywords beside a task spec's: the run's, and where its results go
EVALUATE_RUN = ("max_steps", "workers", "backend", "ray_address")
EVALUATE_OWN = ("out", "episodes", "seed", "video", "on_episode")


def evaluate(
    policy: str = "expert",
    task: TaskSpec | str | None = None,
    *,
    out: str | Path | None = None,
    episodes: int = 10,
    seed: int = EVAL_FIRST_SEED,
    video: int = 0,
    on_episode: Any = None,
    **options: Any,
) -> Evaluation:
    """Score `policy` (expert, zero, random, `module:factory`, or a lerobot checkpoint folder)
    on `task` (a TaskSpec, or a structure's name with the spec's keywords in `options`) over
    `episodes` episodes from seeds `seed`, `seed` + 1, ... (held out from recordings, which
    start at 0); with `out`, write `out/evaluation.json` and film the first `video` episodes.
    A checkpoint is evaluated as it was trained: its cameras, and the robot, structure, size,
    variation, fps and action mode its training saw where not given (a given one that
    contradicts it is refused, but the variation); otherwise pyramid-even, layout, 25 and
    joint. The run's own keywords: `max_steps`, an episode's step limit; `workers` episodes at
    once, in processes or as Ray tasks (`backend="ray"`, at `ray_address` or a Ray started
    here), scoring as one worker does. Returns the `Evaluation` (its scores as
    evaluation.json has them)."""
    from .learning.evaluation.policies import check_spec
    from .learning.evaluation.trained_task import task_given, task_settled
    from .learning.lerobot_plugin.checkpoint_inputs import checkpoint_task, checkpoint_views

    callback_argument(on_episode, "on_episode")
    folder = written.results_folder(out)
    policy = check_spec(policy)
    run = {k: options.pop(k) for k in EVALUATE_RUN if k in options}
    check_keywords(options, (*EVALUATE_RUN, *EVALUATE_OWN))
    settled = checkpoint_task(policy, task_given(task, options))
    views = checkpoint_views(policy)  # a policy trained on cameras sees them again
    spec = task_settled(task, options, settled, views)
    from .learning.evaluation.config import evaluation_of  # MuJoCo: once the task is settled
    from .learning.evaluation.evaluate import evaluate as run_evaluation

    wanted = evaluation_of(policy, spec, {**settled.size, **views}, episodes, seed, video, **run)
    if video and folder is None:
        raise ConfigError("video: films need out; accepted a folder to write them in")
    _prepare_gl(render=bool(video or spec.cameras))
    if folder is None:
        return run_evaluation(wanted, None, on_episode)
    with written.held([(folder, "out")]):
        return run_evaluation(wanted, folder, on_episode)
