"""`pyramid-sim record`: the scripted expert's builds as a LeRobot dataset (v3.0).

An episode is one whole build from its seed (`first_seed + episode`), kept at `fps` with the
cameras asked for. Re-running adds only the episodes missing; an episode is in the dataset
once its files and its record (`meta/pyramid_sim/episode_NNNNNN.json`: its seed, success and
result.json) are in place, which happens together, Ctrl-C and SIGTERM held for that moment.
"""

from __future__ import annotations

import json
import shutil
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from ..config import MotionConfig
from ..errors import ConfigError
from ..output.files import write_atomic
from ..output.video import signals_held
from ..sweep.grid import check_backend
from ..version import __version__
from . import lerobot_format as fmt
from .env import BuildEnv
from .episode import PRIMITIVES, Frame, expert_episode, task_text
from .layout import BRICK_FIELDS, camera_names, check_cameras, check_image_size, control_steps
from .lerobot_meta import write_meta
from .staging import STAGING, land, staged
from .variation import DEFAULT_LEVEL, check_differ, check_level

RECORDS = "meta/pyramid_sim"


@dataclass(frozen=True)
class RecordConfig:
    """What a recording is: the build (structure, size and settings, as `build` takes them),
    how many episodes from which seed, and how they are filmed."""

    structure: str = "pyramid-even"
    options: dict[str, Any] = field(default_factory=dict)  # sizes and settings
    episodes: int = 1
    first_seed: int = 0
    fps: int = 25
    cameras: tuple[str, ...] = ("overview", "left_wrist", "right_wrist")
    image_size: tuple[int, int] = (224, 224)
    variation: str = DEFAULT_LEVEL  # how episodes differ (learning/variation.py)
    randomize: tuple[str, ...] = ()  # parts of learning/randomize.py, drawn per episode
    limit_commands: bool = True  # the environment's: commands within the joints' limits
    workers: int = 1  # episodes filmed at once, each in a process of its own
    backend: str = "process"  # or ray: the episodes as Ray tasks
    ray_address: str | None = None  # with ray: a cluster's (default: a Ray started here)

    def __post_init__(self) -> None:
        if not 1 <= self.episodes <= 100_000:
            raise ConfigError(f"episodes: {self.episodes} is out of range; accepted 1 to 100000")
        control_steps(self.fps, MotionConfig().control_dt)
        check_image_size(self.image_size)
        check_level(self.variation)
        if not 1 <= self.workers <= 64:
            raise ConfigError(f"workers: {self.workers} is out of range; accepted 1 to 64")
        check_backend(self.backend, self.ray_address)
        if not 0 <= self.first_seed <= 2**32 - 1 - self.episodes:
            raise ConfigError(f"seed: {self.first_seed} is out of range; accepted 0 to 2**32 - 1")


@dataclass(frozen=True)
class Recorded:
    """What a recording left: the dataset's folder, its episodes and frames, and how many
    episodes this run added."""

    root: Path
    episodes: int
    frames: int
    added: int
    failed: tuple[int, ...]  # episodes whose build did not succeed (they are kept)


def make_env(config: RecordConfig) -> BuildEnv:
    """The environment a recording's episodes run in, stepping at its frame rate."""
    return BuildEnv(
        config.structure,
        variation=config.variation,
        fps=config.fps,
        limit_commands=config.limit_commands,
        image_size=config.image_size,
        randomize=config.randomize,
        **config.options,
    )


def features(env: BuildEnv, config: RecordConfig) -> dict[str, fmt.Feature]:
    """The dataset's per-frame features, from the environment's layout."""
    names = env.layout.names
    height, width = config.image_size
    bricks = tuple(
        f"brick{slot}.{field}" for slot in range(env.layout.bricks) for field in BRICK_FIELDS
    )
    found = {
        "observation.state": fmt.Feature("float32", (len(names),), names),
        "observation.environment_state": fmt.Feature("float32", (len(bricks),), bricks),
        "action": fmt.Feature("float32", (len(names),), names),
    }
    for camera in config.cameras:
        found[f"observation.images.{camera}"] = fmt.Feature("video", (height, width, 3))
    found["next.reward"] = fmt.Feature("float32", (1,))
    found["next.done"] = fmt.Feature("bool", (1,))
    found["next.success"] = fmt.Feature("bool", (1,))
    for arm in ("left", "right"):
        found[f"primitive.{arm}"] = fmt.Feature("int64", (1,))  # an index into PRIMITIVES
        found[f"brick.{arm}"] = fmt.Feature("int64", (1,))  # build order, -1 for none
    return found


def _frame_values(frame: Frame, cameras: tuple[str, ...]) -> dict[str, Any]:
    values: dict[str, Any] = {
        "observation.state": frame.state,
        "observation.environment_state": frame.environment,
        "action": frame.action,
        "next.reward": frame.reward,
        "next.done": frame.done,
        "next.success": frame.success,
        "primitive.left": frame.primitive[0],
        "primitive.right": frame.primitive[1],
        "brick.left": frame.brick[0],
        "brick.right": frame.brick[1],
    }
    for camera in cameras:
        values[f"observation.images.{camera}"] = frame.images[camera]
    return values


def _records(root: Path) -> dict[int, dict[str, Any]]:
    found = {}
    for path in sorted((root / RECORDS).glob("episode_*.json")):
        record = json.loads(path.read_text())
        found[int(record["episode_index"])] = record
    return found


def _clear_unrecorded(root: Path, recorded: set[int]) -> None:
    """Files of an episode that never made it into the dataset (a run killed outright, or
    halfway through writing), and every temporary file, go."""
    for path in [*root.glob("data/*/*"), *root.glob("videos/*/*/*")]:
        if path.name.endswith(".part"):
            path.unlink()
            continue
        chunk, file = int(path.parent.name.split("-")[1]), int(path.stem.split("-")[1])
        if chunk * fmt.CHUNK_SIZE + file not in recorded:
            path.unlink()
    shutil.rmtree(root / STAGING, ignore_errors=True)


def record(
    out: Path, config: RecordConfig, on_frame: Callable[[int, int], Any] | None = None
) -> Recorded:
    """Record the episodes `out` lacks; `on_frame(episode, frames so far)` after each frame."""
    env = make_env(config)
    check_cameras(config.cameras, env.config.robot_description)
    check_differ(
        config.episodes, config.variation, config.randomize, env.config.layout.spawn_jitter_mm
    )
    feats = features(env, config)
    robot = env.config.robot_description.name
    task = task_text(env)
    extra = _dataset_extra(env, config)
    records = _records(out)
    _check_same_recording(out, records, task, config, feats)
    _clear_unrecorded(out, set(records))
    meta: dict[str, Any] = {
        "fps": config.fps,
        "robot_type": f"{robot}_bimanual",
        "features": feats,
        "task": task,
        "extra": extra,
    }
    added = 0
    missing = [e for e in range(config.episodes) if e not in records]
    try:
        for result in staged(config, env, missing, out, config.workers, on_frame):
            episode, end = result["episode"], result["end"]
            first = sum(r["row"]["length"] for i, r in records.items() if i < episode)
            with signals_held():  # the files and the record land together
                row = land(out, result, first)
                records[episode] = {
                    "episode_index": episode,
                    "seed": config.first_seed + episode,
                    "task": task,
                    "fps": config.fps,
                    "features": list(feats),
                    "success": end.success,
                    "failure": end.failure,
                    "randomization": result["randomization"],
                    "result": end.result,
                    "config": asdict(config),
                    "row": _jsonable(row),
                }
                _write_text(
                    out / RECORDS / f"episode_{episode:06d}.json",
                    json.dumps(records[episode], indent=1) + "\n",
                )
                write_meta(out, [r["row"] for r in records.values()], **meta)
            added += 1
    finally:
        env.close()
        shutil.rmtree(out / STAGING, ignore_errors=True)
    frames = sum(r["row"]["length"] for r in records.values())
    failed = tuple(sorted(i for i, r in records.items() if not r["success"]))
    return Recorded(out, len(records), frames, added, failed)


def _dataset_extra(env: BuildEnv, config: RecordConfig) -> dict[str, Any]:
    """What info.json says of the recording beyond LeRobot's own keys (lerobot ignores it)."""
    spec = env.plan.spec
    named = camera_names(env.config.robot_description)
    return {
        "pyramid_sim": {
            "version": __version__,
            "structure": spec.name,
            "size": dict(spec.size),
            "primitives": list(PRIMITIVES),
            "first_seed": config.first_seed,
            "variation": config.variation,
            "randomize": list(env.randomize),
            "limit_commands": config.limit_commands,
            "cameras": {c: n for c, n in named.items() if c in config.cameras},
        }
    }


def _check_same_recording(
    out: Path,
    records: dict[int, dict[str, Any]],
    task: str,
    config: RecordConfig,
    feats: dict[str, fmt.Feature],
) -> None:
    """ConfigError if `out` holds episodes of another structure, rate or features."""
    for index, rec in records.items():
        variation = rec.get("config", {}).get("variation", config.variation)
        if (
            rec["task"] != task
            or rec["fps"] != config.fps
            or rec["features"] != list(feats)
            or variation != config.variation
        ):
            raise ConfigError(
                f"out: {str(out)!r} holds episodes of another recording (episode {index}: "
                f"{rec['task']!r} at {rec['fps']} fps, variation {variation}); accepted a new "
                "folder or the same "
                "recording's"
            )


def film_episode(
    env: BuildEnv,
    files: fmt.EpisodeFiles,
    config: RecordConfig,
    on_frame: Callable[[int, int], Any] | None,
) -> tuple[Any, dict[str, Any]]:
    """Roll the expert out into `files`; how it ended and its metadata row. A run stopped
    midway leaves none of the episode's files."""
    frames = 0

    def keep(frame: Frame) -> None:
        nonlocal frames
        files.add(_frame_values(frame, config.cameras))
        frames += 1
        if on_frame is not None:
            on_frame(files.episode, frames)

    try:
        end = expert_episode(env, config.first_seed + files.episode, config.cameras, keep)
        return end, files.close()
    except BaseException:
        files.abort()
        raise


def _write_text(path: Path, text: str) -> None:
    write_atomic(path, lambda tmp: tmp.write_text(text))


def _jsonable(row: dict[str, Any]) -> dict[str, Any]:
    import numpy as np

    def convert(value: Any) -> Any:
        if isinstance(value, dict):
            return {k: convert(v) for k, v in value.items()}
        if isinstance(value, np.ndarray):
            return value.tolist()
        if isinstance(value, np.generic):
            return value.item()
        return value

    return convert(row)
