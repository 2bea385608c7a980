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
    DEFAULT_VARIATION,
    EVAL_FIRST_SEED,
    RECORD_CAMERAS,
    RECORD_IMAGE_SIZE,
    RECORD_LINGER,
    ArmChoice,
)
from .config import SimConfig, VideoConfig, check_film
from .core.plan import Plan, make_plan
from .errors import ConfigError, MachineError
from .options import (
    SIZE_KEYWORDS,
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


BUILD_KEYWORDS = ("arms", "video", "snapshot", "video_config", "out", "on_start", "on_placed",
                  "on_frame")  # fmt: skip


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


# record's own keywords: not settings of the build
RECORD_KEYWORDS = ("out", "episodes", "seed", "fps", "cameras", "image_size", "variation",
                   "randomize", "workers", "backend", "ray_address", "noise", "linger",
                   "action_mode", "policy", "beta", "brick_poses", "all_goals", "on_frame", "on_episode",
                   "arms", "repair")  # fmt: skip


def record(
    name: str = "pyramid-even",
    *old_order: Any,
    out: str | Path | None = None,
    arms: ArmChoice = "both",
    episodes: int = 1,
    seed: int = 0,
    fps: int = 25,
    cameras: tuple[str, ...] = RECORD_CAMERAS,
    image_size: tuple[int, int] = RECORD_IMAGE_SIZE,
    variation: str = DEFAULT_VARIATION,
    randomize: tuple[str, ...] = (),
    workers: int = 1,
    backend: str = "process",
    ray_address: str | None = None,
    noise: float = 0.0,
    linger: float = RECORD_LINGER,
    action_mode: str = "joint",
    policy: str | None = None,
    beta: float = 0.5,
    brick_poses: bool = True,
    all_goals: bool = True,
    on_frame: Any = None,
    on_episode: Any = None,
    repair: bool = False,
    config: SimConfig | None = None,
    **options: Any,
) -> Recorded:
    """Record the expert building `name` as a LeRobot dataset (v3.0) in the folder `out`:
    `episodes` builds from seeds `seed`, `seed` + 1, ... at `fps`, `cameras` at `image_size`,
    each drawn at `variation` with its `randomize` parts; `workers` at once (`backend="ray"`:
    Ray tasks, at `ray_address`). `noise` is DART's (rad on each joint in the joint modes, m on
    each hand's x, y, z in the hand modes); a success goes on `linger` s more. With `policy` (as
    `evaluate` takes one), a DAgger round: it drives the 2 s spans the expert does not (a share
    `beta`), the expert labelling every frame. Without `brick_poses`, the bricks' poses (and
    the goals' fill) are left out of the observation; without `all_goals`, every goal but each
    arm's next. Episodes in `out` are kept; a folder holding anything else, or a damaged
    episode (unless `repair`), is refused. `on_frame(episode, frames so far)` and
    `on_episode(episodes in the dataset)` hear progress; `options` as for `build`."""
    folder = _dataset_folder(old_order, out)
    config, spec = resolve(name, config, dict(options), own=RECORD_KEYWORDS)
    for hook, what in ((on_frame, "on_frame"), (on_episode, "on_episode")):
        callback_argument(hook, what)
    from .learning.recording.record import RecordConfig
    from .learning.recording.record import record as run

    sizes = {k: options[k] for k in SIZE_KEYWORDS if k in options}
    settings_ = RecordConfig(
        name, {**sizes, "arms": arms, "config": config}, episodes, seed, fps, cameras,
        image_size, variation, randomize, True, workers, backend, ray_address, noise,
        action_mode, linger, policy, beta, bool(brick_poses), bool(all_goals),
    )  # fmt: skip
    _prepare_gl(render=bool(settings_.cameras))
    from .learning.evaluation.policies import make_policy

    with written.held([(folder, "out")]):
        return run(folder, settings_, on_frame, on_episode, make_policy, repair=bool(repair))


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


EVALUATE_KEYWORDS = ("out", "variation", "fps", "episodes", "seed", "video", "max_steps",
                     "action_mode", "workers", "backend", "ray_address", "on_episode",
                     "arms")  # fmt: skip


def evaluate(
    policy: str = "expert",
    name: str | None = None,
    *,
    out: str | Path | None = None,
    arms: ArmChoice = "both",
    variation: str | None = None,
    fps: int | None = None,
    episodes: int = 10,
    seed: int = EVAL_FIRST_SEED,
    video: int = 0,
    max_steps: int | None = None,
    action_mode: str | None = None,
    workers: int = 1,
    backend: str = "process",
    ray_address: str | None = None,
    on_episode: Any = None,
    config: SimConfig | None = None,
    **options: Any,
) -> Evaluation:
    """Score `policy` (expert, zero, random, `module:factory`, or a lerobot checkpoint folder)
    on `name` over `episodes` episodes from seeds `seed`, `seed` + 1, ... (held out from
    recordings, which start at 0) at `variation` and `fps`; with `out`, write
    `out/evaluation.json` and film the first `video` episodes, the policy acting in
    `action_mode`. A checkpoint is evaluated as it was trained: its cameras, and the robot,
    structure, size, variation, fps and action mode its training saw where not given (a given
    one that contradicts it is refused, but the variation); otherwise pyramid-even, layout, 25
    and joint. `workers` episodes run at once, in processes or as Ray tasks (`backend="ray"`,
    at `ray_address` or a Ray started here), scoring as one worker does. `options` as for
    `build`. Returns the `Evaluation` (its scores as evaluation.json has them)."""
    from .learning.evaluation.policies import check_spec
    from .learning.lerobot_plugin.checkpoint_inputs import Task, checkpoint_task, checkpoint_views

    callback_argument(on_episode, "on_episode")
    folder = written.results_folder(out)
    policy = check_spec(policy)
    options = dict(options)
    sizes = {k: options.pop(k) for k in SIZE_KEYWORDS if k in options}
    robot = config.robot if isinstance(config, SimConfig) else options.get("robot")
    task = checkpoint_task(policy, Task(robot, name, sizes, variation, fps, action_mode))
    assert task.structure is not None and task.variation is not None and task.fps is not None
    if config is None:
        options["robot"] = task.robot
    config, spec = resolve(task.structure, config, {**options, **task.size}, own=EVALUATE_KEYWORDS)
    from .learning.evaluation.config import EvaluateConfig  # MuJoCo: once the task is settled
    from .learning.evaluation.evaluate import evaluate as run

    views = checkpoint_views(policy)  # a policy trained on cameras sees them again
    wanted = EvaluateConfig(
        policy, task.structure, {**task.size, **views, "arms": arms, "config": config},
        task.variation, task.fps, episodes, seed, video, max_steps, task.action_mode or "joint",
        workers, backend, ray_address,
    )  # fmt: skip
    if video and folder is None:
        raise ConfigError("video: films need out; accepted a folder to write them in")
    _prepare_gl(render=bool(video or views))
    if folder is None:
        return run(wanted, None, on_episode)
    with written.held([(folder, "out")]):
        return run(wanted, folder, on_episode)
