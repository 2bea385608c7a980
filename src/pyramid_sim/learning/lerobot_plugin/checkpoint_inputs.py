"""What a lerobot checkpoint was trained on, so that it is evaluated on the same (no lerobot
import): the cameras and their size, read from its config.json (a policy trained on cameras
fails on the first missing image); and the robot, structure, size, variation, step rate and
action mode its training saw (checkpoint_training.py), for whatever is not given. A given one
that contradicts the training is refused: a policy's actions mean what they meant there."""

from __future__ import annotations

import json
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import Any

from ...choices import (
    ACTION_MODE_HAND_ENTRIES,
    ARMS,
    DEFAULT_VARIATION,
    FPS_CHOICES,
    RECORD_ACTION_MODES,
    in_words,
)
from ...errors import ConfigError
from ...robots import DEFAULT_ROBOT, robot
from ..task.observation_names import OBSERVED
from .checkpoint_training import Trained, read_training

IMAGES = "observation.images."
WORDS = {"action_mode": "action mode"}  # as messages name a setting


@dataclass(frozen=True)
class Task:
    """What an evaluation's environment is: as given (None, or no size, where not given), or
    settled."""

    robot: str | None = None
    structure: str | None = None
    size: dict[str, int] = field(default_factory=dict)
    variation: str | None = None
    fps: int | None = None
    action_mode: str | None = None


DEFAULTS = Task(DEFAULT_ROBOT, "pyramid-even", {}, DEFAULT_VARIATION, 25, "joint")


def checkpoint_task(policy: str, given: Task) -> Task:
    """The task `policy` is evaluated on: what is given, what a checkpoint folder's training
    saw for what is not (the variation alone may differ: a test of other episodes), the
    defaults for the rest. ConfigError for a given value that contradicts the training,
    naming both; where the training cannot be read, for a missing action mode or rate, naming
    the modes its action's width fits; and for a mode whose width is not its action's."""
    folder = Path(policy)
    if not (folder / "config.json").is_file():
        return _filled(given)
    trained = read_training(folder)
    if trained is None:
        _refuse_unknown(folder, given)
        task = _filled(given)
    else:
        task = _filled(_agreed(given, trained))
    _check_action_width(folder, task)
    return task


def checkpoint_views(policy: str) -> dict[str, object]:
    """The environment keywords (`cameras`, `image_size`, and what its observation left out,
    `OBSERVED`) a checkpoint folder's policy needs, or nothing for a
    policy that is not a checkpoint or sees no camera. ConfigError for images of different
    sizes, which the environment cannot render at once."""
    trained = read_training(Path(policy)) if Path(policy).is_dir() else None
    hidden = {}
    if trained is not None:  # what its observation left out, left out again
        hidden = {k: False for k in OBSERVED if not getattr(trained.observed, k)}
    return {**_cameras(Path(policy)), **hidden}


def _cameras(policy: Path) -> dict[str, object]:
    """The cameras a checkpoint's config.json says its policy sees, at their size."""
    features = _features(policy, "input_features")
    views = {
        key.removeprefix(IMAGES): tuple(int(n) for n in feature["shape"][-2:])
        for key, feature in features.items()
        if key.startswith(IMAGES)
    }
    if not views:
        return {}
    sizes = set(views.values())
    if len(sizes) > 1:
        raise ConfigError(
            f"policy: its cameras see {sorted(sizes)} (height, width); accepted one size for all"
        )
    return {"cameras": tuple(views), "image_size": sizes.pop()}


def action_entries(robot_name: str, mode: str) -> int:
    """How many entries `robot_name`'s action has in `mode`: its motors' for joint targets,
    five or six a hand for hand poses (`choices.ACTION_MODE_HAND_ENTRIES`)."""
    hand = ACTION_MODE_HAND_ENTRIES[mode]
    if hand is None:
        return sum(len(arm.joints) + 1 for arm in robot(robot_name).arms.values())
    return hand * len(ARMS)


def _filled(task: Task) -> Task:
    """`task` with the defaults where nothing is given."""
    return replace(
        task,
        **{
            f.name: getattr(DEFAULTS, f.name)
            for f in fields(Task)
            if f.name != "size" and getattr(task, f.name) is None
        },
    )


def _agreed(given: Task, trained: Trained) -> Task:
    """What is given, where it agrees with the training, and the training's where not
    given; ConfigError naming both where they differ. The variation may differ, and so may
    the structure's size where the policy saw each arm's next goal alone (its input is the
    same for every size: a policy trained on six bricks meets twenty)."""
    settled: dict[str, Any] = {"variation": given.variation or trained.variation}
    for name in ("robot", "structure", "fps", "action_mode"):
        settled[name] = _same(name, getattr(given, name), getattr(trained, name), trained)
    for name, value in given.size.items():
        if not trained.observed.size_free:
            _same(name, value, trained.size.get(name), trained)
    return Task(size={**trained.size, **given.size}, **settled)


def _same(name: str, given: Any, trained: Any, training: Trained) -> Any:
    if given is None or trained is None or given == trained:
        return trained if given is None else given
    what = WORDS.get(name, name)
    raise ConfigError(
        f"{what}: {given} given, but the checkpoint was trained with {trained} (read from "
        f"{training.source}); accepted {trained}, or no {what} given"
    )


def _refuse_unknown(folder: Path, given: Task) -> None:
    """ConfigError naming what a checkpoint whose training cannot be read needs given."""
    missing = []
    if given.action_mode is None:
        width = _action_width(folder)
        fits = _fitting(given.robot or DEFAULT_ROBOT, width) if width else []
        missing.append(
            f"--action-mode {in_words(tuple(fits))} (what its {width} actions fit)"
            if fits
            else f"--action-mode ({in_words(RECORD_ACTION_MODES)}: its recording's)"
        )
    if given.fps is None:
        missing.append(f"--fps ({in_words(FPS_CHOICES)}: its recording's)")
    if missing:
        raise ConfigError(
            f"policy: {str(folder)!r} does not say how it was trained (no train_config.json "
            "beside it naming a pyramid_sim recording that is there, nor a pyramid_sim env); "
            f"accepted {' and '.join(missing)}"
        )


def _check_action_width(folder: Path, task: Task) -> None:
    assert task.robot is not None and task.action_mode is not None
    width = _action_width(folder)
    wanted = action_entries(task.robot, task.action_mode)
    if width is None or wanted is None or width == wanted:
        return
    fits = _fitting(task.robot, width)
    raise ConfigError(
        f"action mode: {task.action_mode} acts with {wanted} entries on {task.robot}, but the "
        f"checkpoint's action has {width}; accepted "
        + (in_words(fits) if fits else f"its robot's (none of {task.robot}'s modes has {width})")
    )


def _fitting(robot_name: str, width: int) -> list[str]:
    return [m for m in RECORD_ACTION_MODES if action_entries(robot_name, m) == width]


def _action_width(folder: Path) -> int | None:
    shape = (_features(folder, "output_features").get("action") or {}).get("shape") or []
    return int(shape[-1]) if shape else None


def _features(folder: Path, kind: str) -> dict[str, Any]:
    """config.json's input or output features, or none where it is not there."""
    config = folder / "config.json"
    if not config.is_file():
        return {}
    try:
        features = json.loads(config.read_text()).get(kind) or {}
    except (OSError, ValueError, AttributeError) as err:
        raise ConfigError(f"policy: {str(config)!r} cannot be read ({err})") from None
    return dict(features)
